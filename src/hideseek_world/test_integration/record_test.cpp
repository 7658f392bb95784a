// Runs against basic.launch with record:=true (see record.test): after a few episodes it asks
// the recorder to shut down, as Ctrl-C or `rosnode kill` would, then opens the bag with the C++
// rosbag API and checks that every recorded topic is there, from the game's first decision.
#include <dirent.h>
#include <gtest/gtest.h>
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/StepBatch.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <xmlrpcpp/XmlRpc.h>

#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include "test_helpers.h"

namespace {

std::string findBag(const std::string& dir, bool finished) {
  DIR* d = opendir(dir.c_str());
  if (!d) return "";
  std::string found;
  while (dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    const std::string suffix = finished ? ".bag" : ".bag.active";
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      found = dir + "/" + name;
    }
  }
  closedir(d);
  return found;
}

bool shutdownNode(const std::string& node) {
  const std::string uri = hideseek_test::nodeUri(node);
  std::string host;
  uint32_t port = 0;
  if (uri.empty() || !ros::network::splitURI(uri, host, port)) return false;
  XmlRpc::XmlRpcClient client(host.c_str(), port, "/");
  XmlRpc::XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  request[1] = "record_test: done recording";
  return client.execute("shutdown", request, response);
}

TEST(Record, BagClosesCleanlyAndHoldsEveryListedTopic) {
  ros::NodeHandle nh, pnh("~");
  const std::string dir = pnh.param<std::string>("bag_dir", "");
  std::vector<std::string> topics;
  ASSERT_TRUE(pnh.getParam("topics", topics));
  int finished = 0;
  auto sub =
      nh.subscribe<hideseek_msgs::GameState>("game_state", 100, [&](const hideseek_msgs::GameState::ConstPtr& m) {
        finished += m->outcome != hideseek_msgs::GameState::OUTCOME_RUNNING;
      });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(120.0);
  while (ros::ok() && (finished < 3 || findBag(dir, false).empty()) && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  ASSERT_GE(finished, 3);
  ros::WallDuration(1.0).sleep();  // let the recorder write what it buffered
  ASSERT_TRUE(shutdownNode("/recorder"));
  std::string bag_path;
  const ros::WallTime closed = ros::WallTime::now() + ros::WallDuration(30.0);
  while ((bag_path = findBag(dir, true)).empty() && ros::WallTime::now() < closed) ros::WallDuration(0.1).sleep();
  ASSERT_FALSE(bag_path.empty()) << "no closed .bag in " << dir;
  EXPECT_NE(bag_path.find("basic_seed0"), std::string::npos) << "bags are named by variant and seed: " << bag_path;

  rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::map<std::string, int> counts;
  for (const rosbag::MessageInstance& m : view) counts[m.getTopic()]++;
  for (const std::string& t : topics) EXPECT_GT(counts[t], 0) << "topic " << t << " missing from " << bag_path;
  int outcomes = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/game_state"))) {
    const auto state = m.instantiate<hideseek_msgs::GameState>();
    ASSERT_TRUE(state);
    outcomes += state->outcome != hideseek_msgs::GameState::OUTCOME_RUNNING;
  }
  EXPECT_GE(outcomes, 3) << "finished episodes are in the bag";
  // The game waits for the recorder (record:=true adds it to the world's step and episode
  // listeners): the bag's first step record is the game's first decision. (rosbag's queue of 100
  // may still drop a record on a loaded machine: the holes are counted, not failed.)
  std::vector<uint64_t> decisions;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/world/steps"))) {
    const auto steps = m.instantiate<hideseek_msgs::StepBatch>();
    ASSERT_TRUE(steps);
    decisions.push_back(steps->decision);
  }
  ASSERT_FALSE(decisions.empty()) << "no /world/steps in " << bag_path;
  EXPECT_EQ(decisions.front(), 0u) << "the recording missed the game's first decisions";
  for (size_t k = 1; k < decisions.size(); ++k) {
    ASSERT_GT(decisions[k], decisions[k - 1]) << "step records out of order at " << k;
  }
  std::cout << "record_test: " << decisions.size() << " step records, decisions " << decisions.front() << ".."
            << decisions.back() << ", " << (decisions.back() + 1 - decisions.size()) << " missing\n";
  bag.close();
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "record_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
