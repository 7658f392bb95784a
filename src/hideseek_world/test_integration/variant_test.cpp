// Runs against a variant launch file with the random hider (see variant_*.test, realtime.test):
// the three agents are separate processes, episodes end by capture or by the step limit, every
// decision applies the action chosen for its own step, a reset does not stall the game, and the
// frames carry the game's prefix. Every check runs on every launch: none is skipped.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PointStamped.h>
#include <gtest/gtest.h>
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <hideseek_msgs/Reset.h>
#include <hideseek_msgs/StepBatch.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <tf2_ros/transform_listener.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/topic_names.h"
#include "test_helpers.h"

namespace {

using hideseek_test::nodeUri;

TEST(Variant, WorldSeekerAndHiderAreSeparateProcesses) {
  std::set<std::string> uris;
  // Relative names: the test runs in the game's namespace (two_games.test runs two).
  for (const std::string node :
       {ros::names::resolve("world"), ros::names::resolve("seeker"), ros::names::resolve("hider")}) {
    std::string uri;
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
    while ((uri = nodeUri(node)).empty() && ros::WallTime::now() < end) ros::WallDuration(0.1).sleep();
    ASSERT_FALSE(uri.empty()) << node << " is not running";
    uris.insert(uri);
  }
  EXPECT_EQ(uris.size(), 3u) << "each node has its own XML-RPC server, so its own process";
}

TEST(Variant, EpisodesEndByCaptureOrStepLimit) {
  ros::NodeHandle nh, pnh("~");
  const int wanted = pnh.param("episodes", 8);
  const double min_capture = pnh.param("min_capture_fraction", 0.0);
  const int max_steps = pnh.param("max_steps", 1000);
  int captured = 0, survived = 0;
  std::vector<uint32_t> last_step;
  std::set<uint32_t> seeds;
  auto sub = nh.subscribe<hideseek_msgs::ObservationBatch>(
      "hider/observations", 10, [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) {
        if (last_step.size() != m->num_arenas) last_step.assign(m->num_arenas, 0);
        for (size_t i = 0; i < m->num_arenas; ++i) {
          if (m->done[i]) {
            if (m->outcome[i] == hideseek_msgs::GameState::OUTCOME_CAPTURED) {
              ++captured;
            } else {
              EXPECT_EQ(m->outcome[i], hideseek_msgs::GameState::OUTCOME_SURVIVED);
              EXPECT_EQ(last_step[i] + 1, static_cast<uint32_t>(max_steps)) << "survival only at the step limit";
              ++survived;
            }
            seeds.insert(m->seed[i]);
          }
          last_step[i] = m->step[i];
        }
      });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(240.0);
  while (ros::ok() && captured + survived < wanted && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.002).sleep();
  }
  ASSERT_GE(captured + survived, wanted) << "episodes did not finish";
  EXPECT_GE(captured, min_capture * (captured + survived)) << captured << " captures in " << captured + survived;
  EXPECT_GE(seeds.size(), static_cast<size_t>(wanted) / 2) << "new episodes start with new seeds";
}

// The random hider's action is a function of (seed, step) only, so world/steps shows whether the
// world applied each answer to the step it was chosen for: in realtime a late answer used to be
// applied to the next step, and the hider's previous action repeated.
TEST(Variant, EveryDecisionAppliesTheActionChosenForItsOwnStep) {
  ros::NodeHandle nh, pnh("~");
  const int wanted = pnh.param("own_step_decisions", 40);
  std::vector<hideseek_msgs::StepBatch> got;
  auto sub =
      nh.subscribe<hideseek_msgs::StepBatch>("world/steps", 1000, [&](const hideseek_msgs::StepBatch::ConstPtr& m) {
        if (static_cast<int>(got.size()) < wanted) got.push_back(*m);
      });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(120.0);
  while (ros::ok() && static_cast<int>(got.size()) < wanted && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.002).sleep();
  }
  ASSERT_EQ(static_cast<int>(got.size()), wanted) << "world/steps did not carry enough decisions";
  int mismatches = 0, checked = 0;
  for (size_t k = 0; k < got.size(); ++k) {
    const auto& b = got[k];
    if (k > 0) EXPECT_EQ(b.decision, got[k - 1].decision + 1) << "world/steps lost a decision";
    ASSERT_EQ(b.hider_action.size(), b.num_arenas);
    ASSERT_EQ(b.seed.size(), b.num_arenas);
    for (size_t i = 0; i < b.num_arenas; ++i, ++checked) {
      const uint8_t expected = hideseek_game::hashAction(b.seed[i], b.step[i], hideseek_game::kSaltRandomHider);
      if (b.hider_action[i] != expected) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0) << mismatches << " of " << checked << " arena steps applied another step's action";
}

// Diagnostics say how fast the game runs and, while the game is healthy, report OK.
TEST(Variant, DiagnosticsReportRateAndNoRejectedActions) {
  ros::NodeHandle nh;
  std::vector<diagnostic_msgs::DiagnosticStatus> reports;
  auto sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status) {
          if (st.name == hideseek_game::worldDiagnosticName(ros::this_node::getNamespace())) reports.push_back(st);
        }
      });
  // The first report after subscribing may cover less than a second: take the third.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && reports.size() < 3 && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  ASSERT_GE(reports.size(), 3u) << "no diagnostics from the world";
  std::map<std::string, std::string> v;
  for (const auto& kv : reports.back().values) v[kv.key] = kv.value;
  EXPECT_GT(std::stod(v["decision_steps_per_s"]), 0.0);
  EXPECT_GT(std::stod(v["real_time_factor"]), 0.0);
  // In lockstep a stalled game re-sends its observation (resend_period), and the agents' second
  // answers to it can arrive after the step: those refusals are by design. Realtime never re-sends.
  if (ros::NodeHandle("~").param("expect_no_wrong_step", false)) EXPECT_EQ(v["rejected_wrong_step"], "0");
  EXPECT_EQ(v["rejected_late"], "0");
  EXPECT_EQ(reports.back().level, diagnostic_msgs::DiagnosticStatus::OK) << reports.back().message;
}

// A reset re-sends the observation at the same sim time with new step ids; the agents must answer
// it afresh (a cached answer carried the old step ids and lockstep waited for ever).
TEST(Variant, ResetDoesNotStallTheGame) {
  ros::NodeHandle nh;
  uint32_t max_step = 0;
  std::set<uint32_t> seeds;
  bool restarted = false;  // arena 0 showed step 0 of the reset's seed
  // Lockstep runs fast: a deep queue keeps the batches after the reset.
  auto sub = nh.subscribe<hideseek_msgs::ObservationBatch>("hider/observations", 2000,
                                                           [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) {
                                                             if (m->num_arenas == 0) return;
                                                             if (!restarted)
                                                               restarted = m->seed[0] == 700 && m->step[0] == 0;
                                                             if (!restarted) return;
                                                             for (size_t i = 0; i < m->num_arenas; ++i) {
                                                               seeds.insert(m->seed[i]);
                                                               max_step = std::max(max_step, m->step[i]);
                                                             }
                                                           });
  ASSERT_TRUE(ros::service::waitForService("world/reset", 30000));
  // Connected before the reset, so that its first batch is not missed.
  const ros::WallTime connect_end = ros::WallTime::now() + ros::WallDuration(10.0);
  while (sub.getNumPublishers() == 0 && ros::WallTime::now() < connect_end) ros::WallDuration(0.01).sleep();
  ros::WallDuration(0.2).sleep();
  hideseek_msgs::Reset reset;
  reset.request.arena = -1;
  reset.request.seed = 700;
  ASSERT_TRUE(ros::service::call("world/reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && max_step < 10 && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.002).sleep();
  }
  ASSERT_TRUE(restarted) << "arena 0 did not restart with the reset's seed";
  EXPECT_GE(max_step, 10u) << "the game stalled after a reset";
  EXPECT_GE(*seeds.begin(), 700u) << "an episode of before the reset went on";
}

// A game names its frames with its prefix (two_games.test: game1/map, ...), or none at the root
// (map, hider/base_link, ...): its latched map and the TF chains from its map to both cameras.
TEST(Variant, FramesCarryTheGamesTfPrefix) {
  ros::NodeHandle nh, pnh("~");
  const std::string prefix = pnh.param<std::string>("expect_tf_prefix", "");
  const auto frame = [&](const std::string& name) { return prefix.empty() ? name : prefix + "/" + name; };
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  nav_msgs::OccupancyGrid::ConstPtr map;
  auto sub =
      nh.subscribe<nav_msgs::OccupancyGrid>("map", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) { map = m; });
  ASSERT_TRUE(hideseek_test::waitFor([&] { return map != nullptr; }, 20.0))
      << "no latched map in " << nh.getNamespace();
  EXPECT_EQ(map->header.frame_id, frame("map"));
  for (const std::string agent : {"hider", "seeker"}) {
    const std::string camera = frame(agent + "/camera_optical_frame");
    EXPECT_TRUE(hideseek_test::waitFor([&] { return buffer.canTransform(frame("map"), camera, ros::Time(0)); }, 10.0))
        << frame("map") << " to " << camera;
  }
}

// The scripted seeker shows what it follows (docs/architecture.md, topics): arena 0's plan on
// seeker/plan (its pose, then the path) and the point it heads for on seeker/target, in the game's
// map frame, inside the arena, the target a point of the path published with it (or, where the
// seeker has no path and stays, its own position, the plan's only pose).
TEST(Variant, TheSeekerShowsItsPlanAndTargetInTheMapFrame) {
  ros::NodeHandle nh, pnh("~");
  const std::string prefix = pnh.param<std::string>("expect_tf_prefix", "");
  const std::string map_frame = prefix.empty() ? "map" : prefix + "/map";
  nav_msgs::OccupancyGrid::ConstPtr map;
  auto map_sub =
      nh.subscribe<nav_msgs::OccupancyGrid>("map", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) { map = m; });
  ASSERT_TRUE(hideseek_test::waitFor([&] { return map != nullptr; }, 20.0)) << "no latched map";
  const double half_extent = 0.5 * map->info.width * map->info.resolution;
  std::vector<nav_msgs::Path::ConstPtr> plans;
  std::vector<geometry_msgs::PointStamped::ConstPtr> targets;
  auto plan_sub = nh.subscribe<nav_msgs::Path>(hideseek_game::kSeekerPlanTopic, 100,
                                               [&](const nav_msgs::Path::ConstPtr& m) { plans.push_back(m); });
  auto target_sub = nh.subscribe<geometry_msgs::PointStamped>(
      hideseek_game::kSeekerTargetTopic, 100,
      [&](const geometry_msgs::PointStamped::ConstPtr& m) { targets.push_back(m); });
  ASSERT_TRUE(hideseek_test::waitFor([&] { return plans.size() >= 3 && targets.size() >= 3; }, 30.0))
      << plans.size() << " plans and " << targets.size() << " targets in 30 s on " << nh.resolveName("seeker/plan");
  plan_sub.shutdown();
  target_sub.shutdown();
  // A target goes out with the plan of its decision, under the same header; the two topics arrive
  // on two connections, so a target is checked against the plans of its stamp when they came (in
  // lockstep a step's several seeker decisions share a stamp).
  std::multimap<ros::Time, nav_msgs::Path::ConstPtr> plans_at;
  size_t points = 0;
  for (const auto& plan : plans) {
    EXPECT_EQ(plan->header.frame_id, map_frame);
    for (const auto& pose : plan->poses) {
      EXPECT_LT(std::max(std::abs(pose.pose.position.x), std::abs(pose.pose.position.y)), half_extent)
          << "a plan point outside the arena";
    }
    points += plan->poses.size();
    plans_at.emplace(plan->header.stamp, plan);
  }
  EXPECT_GT(points, plans.size()) << "no plan held more than the seeker's pose";
  int paired = 0;
  for (const auto& t : targets) {
    EXPECT_EQ(t->header.frame_id, map_frame);
    const auto [first, last] = plans_at.equal_range(t->header.stamp);
    if (first == last) continue;
    ++paired;
    const bool on_a_plan = std::any_of(first, last, [&](const auto& entry) {
      const auto& poses = entry.second->poses;
      return std::any_of(
          poses.begin() + (poses.size() > 1 ? 1 : 0), poses.end(), [&](const geometry_msgs::PoseStamped& p) {
            return std::abs(p.pose.position.x - t->point.x) < 1e-6 && std::abs(p.pose.position.y - t->point.y) < 1e-6;
          });
    });
    EXPECT_TRUE(on_a_plan) << "target (" << t->point.x << ", " << t->point.y << ") is on no plan of its stamp";
  }
  EXPECT_GT(paired, 0) << "no target came with a plan of the same stamp";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "variant_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
