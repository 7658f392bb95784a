// Launches against the real world node (see world_node.test) and checks what a ROS user sees.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/EpisodeResult.h>
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <hideseek_msgs/Reset.h>
#include <hideseek_msgs/SeekerObservationBatch.h>
#include <hideseek_msgs/StepBatch.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <functional>
#include <map>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/params.h"
#include "test_helpers.h"

namespace {

using hideseek_test::waitFor;

constexpr int kArenas = 2;

class WorldNodeTest : public testing::Test {
 protected:
  void SetUp() override {
    hider_obs_sub_ = nh_.subscribe<hideseek_msgs::ObservationBatch>(
        "hider/observations", 10, [this](const hideseek_msgs::ObservationBatch::ConstPtr& m) { hider_obs_ = m; });
    seeker_obs_sub_ = nh_.subscribe<hideseek_msgs::SeekerObservationBatch>(
        "seeker/observations", 10,
        [this](const hideseek_msgs::SeekerObservationBatch::ConstPtr& m) { seeker_obs_ = m; });
    hider_pub_ = nh_.advertise<hideseek_msgs::ActionBatch>("hider/actions", 10);
    seeker_pub_ = nh_.advertise<hideseek_msgs::ActionBatch>("seeker/actions", 10);
    ASSERT_TRUE(waitFor([&] { return hider_obs_ && seeker_obs_; }, 30.0)) << "no observations from the world";
    ASSERT_TRUE(
        waitFor([&] { return hider_pub_.getNumSubscribers() > 0 && seeker_pub_.getNumSubscribers() > 0; }, 10.0));
  }

  hideseek_msgs::ActionBatch batch(uint8_t action, const std::vector<uint32_t>& steps) {
    hideseek_msgs::ActionBatch b;
    b.actions.assign(steps.size(), action);
    b.step = steps;
    return b;
  }

  // Answers the current observation for both agents, and the seeker's later decisions inside the
  // step (game v2's seeker decides every frame), and waits for the next step's observation: one
  // with a later stamp. A re-send of the same step (resend_period) can be queued when this starts,
  // however slow the machine, and a new pointer alone would take it for the next step.
  bool playStep(uint8_t hider_action, uint8_t seeker_action) {
    const auto before = hider_obs_;
    auto answered = seeker_obs_;
    hider_pub_.publish(batch(hider_action, before->step));
    seeker_pub_.publish(batch(seeker_action, answered->step));
    return waitFor(
        [&] {
          if (hider_obs_->header.stamp == before->header.stamp && seeker_obs_ != answered) {
            answered = seeker_obs_;
            seeker_pub_.publish(batch(seeker_action, answered->step));
          }
          return hider_obs_->header.stamp > before->header.stamp;
        },
        10.0);
  }

  ros::NodeHandle nh_;
  ros::Subscriber hider_obs_sub_, seeker_obs_sub_;
  ros::Publisher hider_pub_, seeker_pub_;
  hideseek_msgs::ObservationBatch::ConstPtr hider_obs_;
  hideseek_msgs::SeekerObservationBatch::ConstPtr seeker_obs_;
};

TEST_F(WorldNodeTest, ObservationBatchesCarryEveryArena) {
  EXPECT_EQ(hider_obs_->num_arenas, static_cast<uint32_t>(kArenas));
  EXPECT_EQ(hider_obs_->images.size(), static_cast<size_t>(kArenas) * 84 * 84 * 3);
  EXPECT_EQ(hider_obs_->step.size(), static_cast<size_t>(kArenas));
  EXPECT_EQ(hider_obs_->seed[0], 5u);
  EXPECT_EQ(hider_obs_->seed[1], 6u);
  EXPECT_EQ(seeker_obs_->maps.size(), static_cast<size_t>(kArenas));
  EXPECT_EQ(seeker_obs_->maps[0].obstacles.size(), 20u);  // config/maps/deterministic.yaml
  for (int i = 0; i < kArenas; ++i) {
    if (!seeker_obs_->sees_hider[i]) {
      EXPECT_EQ(seeker_obs_->hider_position[i].x, 0.0) << "the seeker must not learn where an unseen hider is";
      EXPECT_EQ(seeker_obs_->hider_position[i].y, 0.0);
    }
  }
}

TEST_F(WorldNodeTest, CameraImageHasSizeEncodingAndOpticalFrame) {
  sensor_msgs::Image::ConstPtr image;
  sensor_msgs::CameraInfo::ConstPtr info;
  auto s1 = nh_.subscribe<sensor_msgs::Image>("hider/camera/image_raw", 1,
                                              [&](const sensor_msgs::Image::ConstPtr& m) { image = m; });
  auto s2 = nh_.subscribe<sensor_msgs::CameraInfo>("hider/camera/camera_info", 1,
                                                   [&](const sensor_msgs::CameraInfo::ConstPtr& m) { info = m; });
  ASSERT_TRUE(waitFor([&] { return s1.getNumPublishers() > 0 && s2.getNumPublishers() > 0; }, 5.0));
  ros::WallDuration(0.3).sleep();
  ASSERT_TRUE(playStep(0, 0));
  ASSERT_TRUE(waitFor([&] { return image && info; }, 10.0));
  EXPECT_EQ(image->width, 84u);
  EXPECT_EQ(image->height, 84u);
  EXPECT_EQ(image->encoding, "rgb8");
  EXPECT_EQ(image->step, 84u * 3);
  EXPECT_EQ(image->header.frame_id, "hider/camera_optical_frame");
  EXPECT_EQ(info->header.frame_id, "hider/camera_optical_frame");
  EXPECT_NEAR(info->K[0], 42.0 / std::tan(60.0 * M_PI / 180.0), 1e-6);
  // Pixel centres at integer coordinates: the symmetric frustum's centre is pixel 41.5.
  EXPECT_DOUBLE_EQ(info->K[2], 41.5);
  EXPECT_DOUBLE_EQ(info->K[5], 41.5);
  EXPECT_DOUBLE_EQ(info->P[2], 41.5);
  // The image is the arena-0 image of the batch (visuals go out at most 30 times a wall second).
  ros::WallDuration(0.1).sleep();
  image.reset();
  ASSERT_TRUE(playStep(0, 0));
  const auto obs = hider_obs_;
  ASSERT_TRUE(waitFor([&] { return image && image->header.stamp == obs->header.stamp; }, 10.0));
  EXPECT_TRUE(std::equal(image->data.begin(), image->data.end(), obs->images.begin()));
}

// Every node reads its parameters through one header: values are checked, and an error names
// the parameter as the user would set it.
TEST(Params, CheckTypeAndRangeAndNameTheParameter) {
  ros::NodeHandle pnh("~params_test");
  pnh.setParam("count", 5);
  pnh.setParam("word", std::string("lockstep"));
  pnh.setParam("flag", true);
  pnh.setParam("rate", 2.5);
  EXPECT_EQ(hideseek_game::readInt(pnh, "count", 1, 1, 10), 5);
  EXPECT_EQ(hideseek_game::readInt(pnh, "missing", 3, 1, 10), 3);
  EXPECT_DOUBLE_EQ(hideseek_game::readDouble(pnh, "rate", 1.0, 0.0, 10.0), 2.5);
  EXPECT_TRUE(hideseek_game::readBool(pnh, "flag", false));
  EXPECT_EQ(hideseek_game::readChoice(pnh, "word", "realtime", {"realtime", "lockstep"}), "lockstep");
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] {
              hideseek_game::readInt(pnh, "count", 1, 6, 10);
            }).find("params_test/count must be in [6, 10], got 5"),
            std::string::npos);
  // A bound is written as a user writes it, not as 1000000000000.000000 (train.launch's steps:=-100).
  EXPECT_NE(message([&] {
              hideseek_game::readDouble(pnh, "count", 6.0, 6.0, 1e12);
            }).find("params_test/count must be in [6, 1000000000000], got 5"),
            std::string::npos);
  EXPECT_NE(message([&] {
              hideseek_game::readDouble(pnh, "count", 1.0, 0.05, 2.5);
            }).find("params_test/count must be in [0.05, 2.5], got 5"),
            std::string::npos);
  EXPECT_NE(message([&] { hideseek_game::readInt(pnh, "word", 1, 0, 10); }).find("params_test/word must be an integer"),
            std::string::npos);
  EXPECT_NE(message([&] { hideseek_game::readBool(pnh, "count", false); }).find("must be true or false"),
            std::string::npos);
  EXPECT_NE(message([&] {
              hideseek_game::readChoice(pnh, "word", "a", {"a", "b"});
            }).find("must be one of 'a', 'b', got 'lockstep'"),
            std::string::npos);
  EXPECT_NE(message([&] {
              hideseek_game::requireString(pnh, "nothing", "a file path");
            }).find("params_test/nothing is required (a file path)"),
            std::string::npos);
}

// A node given a variant and no game plays config/games.yaml's default, and its ~game then says
// which game that was (rosparam get /hider/game); a game named stays as it was named.
TEST(Params, ANodeGivenNoGameWritesTheDefaultItPlaysIntoItsGameParameter) {
  ros::NodeHandle unnamed("~variant_params_test");
  unnamed.setParam("variant", std::string("basic"));
  const hideseek_game::VariantConfig v = hideseek_game::loadVariantParams(unnamed);
  std::string game;
  ASSERT_TRUE(unnamed.getParam("game", game));
  EXPECT_EQ(game, hideseek_game::defaultGame(hideseek_game::configDirectory()));
  EXPECT_EQ(game, v.game.name);
  ros::NodeHandle named("~variant_params_named_test");
  named.setParam("variant", std::string("basic"));
  named.setParam("game", std::string("v2"));
  EXPECT_EQ(hideseek_game::loadVariantParams(named).game.name, "v2");
  ASSERT_TRUE(named.getParam("game", game));
  EXPECT_EQ(game, "v2");
}

TEST_F(WorldNodeTest, TfTreeJoinsMapToBothCameraOpticalFrames) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(playStep(3, 3));
  for (const std::string agent : {"hider", "seeker"}) {
    // The world sends tf as it steps: keep stepping until the listener has caught up.
    ASSERT_TRUE(waitFor(
        [&] { return playStep(3, 3) && buffer.canTransform("map", agent + "/camera_optical_frame", ros::Time(0)); },
        10.0))
        << agent;
    const auto t = buffer.lookupTransform("map", agent + "/camera_optical_frame", ros::Time(0));
    EXPECT_NEAR(t.transform.translation.z, 1.0, 1e-9) << "camera at 1.0 m";
  }
}

TEST_F(WorldNodeTest, MapIsLatchedForLateSubscribers) {
  nav_msgs::OccupancyGrid::ConstPtr map;
  auto sub =
      nh_.subscribe<nav_msgs::OccupancyGrid>("map", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) { map = m; });
  ASSERT_TRUE(waitFor([&] { return map != nullptr; }, 10.0))
      << "a late subscriber must get the map without a new episode";
  EXPECT_EQ(map->header.frame_id, "map");
  EXPECT_NEAR(map->info.origin.position.x, -7.0, 1e-9);
  EXPECT_EQ(map->info.width * map->info.resolution, 14.0f);
  int occupied = 0;
  for (int8_t c : map->data) occupied += c == 100;
  EXPECT_GT(occupied, 0);
  EXPECT_LT(occupied, static_cast<int>(map->data.size()) / 2);
}

TEST_F(WorldNodeTest, MarkersShowObstaclesAgentsAndViewCones) {
  visualization_msgs::MarkerArray::ConstPtr markers;
  auto sub = nh_.subscribe<visualization_msgs::MarkerArray>(
      "world/markers", 1, [&](const visualization_msgs::MarkerArray::ConstPtr& m) { markers = m; });
  ASSERT_TRUE(waitFor([&] { return sub.getNumPublishers() > 0; }, 5.0));
  ros::WallDuration(0.3).sleep();
  ASSERT_TRUE(waitFor([&] { return playStep(0, 0) && markers != nullptr; }, 10.0));
  std::map<std::string, int> by_ns;
  for (const auto& m : markers->markers) by_ns[m.ns]++;
  EXPECT_EQ(by_ns["obstacles"], 16);  // config/maps/deterministic.yaml
  EXPECT_EQ(by_ns["wall_cuts"], 4);
  EXPECT_EQ(by_ns["walls"], 4);
  EXPECT_EQ(by_ns["hider"], 1);
  EXPECT_EQ(by_ns["seeker"], 1);
  EXPECT_EQ(by_ns["hider_view"], 1);
  EXPECT_EQ(by_ns["seeker_view"], 1);
}

TEST_F(WorldNodeTest, LockstepEpisodeRunsToCaptureOrStepLimit) {
  // The seeker walks forward (it starts facing the hider), the hider stands: arena 0 ends by
  // capture, or by the step limit when an obstacle stands between them.
  hideseek_msgs::GameState::ConstPtr last;
  auto sub = nh_.subscribe<hideseek_msgs::GameState>("game_state", 2000,
                                                     [&](const hideseek_msgs::GameState::ConstPtr& m) { last = m; });
  ASSERT_TRUE(waitFor([&] { return sub.getNumPublishers() > 0; }, 5.0));
  const uint32_t episode = hider_obs_->episode[0];
  uint32_t last_step = hider_obs_->step[0];
  for (int i = 0; i < 1100; ++i) {
    ASSERT_TRUE(playStep(0, 1)) << "world stopped answering at step " << i;
    if (hider_obs_->done[0]) {
      const uint8_t outcome = hider_obs_->outcome[0];
      EXPECT_TRUE(outcome == hideseek_msgs::GameState::OUTCOME_CAPTURED ||
                  (outcome == hideseek_msgs::GameState::OUTCOME_SURVIVED && last_step + 1 == 1000u));
      if (outcome == hideseek_msgs::GameState::OUTCOME_CAPTURED) EXPECT_FLOAT_EQ(hider_obs_->rewards[0], -1.f);
      EXPECT_EQ(hider_obs_->episode[0], episode + 1);
      EXPECT_EQ(hider_obs_->step[0], 0u);
      ASSERT_TRUE(waitFor([&] { return last && last->outcome != 0; }, 5.0));
      EXPECT_EQ(last->outcome, outcome);
      if (outcome == hideseek_msgs::GameState::OUTCOME_CAPTURED) EXPECT_LE(last->distance, 0.8f);
      return;
    }
    EXPECT_EQ(hider_obs_->step[0], last_step + 1);
    EXPECT_FLOAT_EQ(hider_obs_->rewards[0], 0.001f);
    last_step = hider_obs_->step[0];
  }
  FAIL() << "episode did not end within 1000 steps";
}

TEST_F(WorldNodeTest, MalformedInputIsRejectedCountedAndTheWorldKeepsServing) {
  diagnostic_msgs::DiagnosticArray::ConstPtr diag;
  auto sub = nh_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10,
                                                             [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
                                                               for (const auto& s : m->status) {
                                                                 if (s.name == "hideseek world: input") diag = m;
                                                               }
                                                             });
  const auto before = hider_obs_;
  // Wrong arena count, an out-of-range action, a stale step id.
  hider_pub_.publish(batch(1, {before->step[0]}));
  auto bad_action = batch(1, before->step);
  bad_action.actions[1] = 9;
  seeker_pub_.publish(bad_action);
  auto stale = batch(1, before->step);
  stale.step[0] += 7;
  hider_pub_.publish(stale);
  // A second process publishing hider actions: the intruder node answers what we feed it.
  ros::Publisher feed = nh_.advertise<hideseek_msgs::ObservationBatch>("intruder/observations", 1);
  ASSERT_TRUE(waitFor([&] { return feed.getNumSubscribers() > 0; }, 10.0));
  feed.publish(*before);
  // The incomplete batches must not advance the world.
  ros::WallDuration(0.2).sleep();
  ros::spinOnce();
  EXPECT_EQ(hider_obs_->step, before->step);
  // Correct actions are still served.
  ASSERT_TRUE(playStep(0, 0));
  EXPECT_NE(hider_obs_->header.stamp, before->header.stamp);
  std::map<std::string, std::string> counts;
  ASSERT_TRUE(waitFor(
      [&] {
        if (!diag) return false;
        std::map<std::string, std::string> v;
        for (const auto& s : diag->status) {
          for (const auto& kv : s.values) v[kv.key] = kv.value;
        }
        counts = v;
        return v["rejected_wrong_arena_count"] != "0" && v["rejected_invalid_action"] != "0" &&
               v["rejected_wrong_step"] != "0" && v["rejected_second_publisher"] != "0";
      },
      5.0))
      << "rejections are counted in /diagnostics: arena count " << counts["rejected_wrong_arena_count"] << ", action "
      << counts["rejected_invalid_action"] << ", step " << counts["rejected_wrong_step"] << ", second publisher "
      << counts["rejected_second_publisher"];
}

// In lockstep an unanswered step is re-sent after resend_period, to the agent that has not
// answered only: the other's answer is in, and a second answer from it could arrive after the step
// moved on, to be refused as a wrong step.
TEST_F(WorldNodeTest, ALockstepReSendGoesOnlyToTheAgentThatHasNotAnswered) {
  int hider_batches = 0, seeker_batches = 0;
  auto hider_count = nh_.subscribe<hideseek_msgs::ObservationBatch>(
      "hider/observations", 10, [&](const hideseek_msgs::ObservationBatch::ConstPtr&) { ++hider_batches; });
  auto seeker_count = nh_.subscribe<hideseek_msgs::SeekerObservationBatch>(
      "seeker/observations", 10, [&](const hideseek_msgs::SeekerObservationBatch::ConstPtr&) { ++seeker_batches; });
  ASSERT_TRUE(waitFor([&] { return hider_count.getNumPublishers() > 0 && seeker_count.getNumPublishers() > 0; }, 5.0));
  const auto step = hider_obs_;
  seeker_pub_.publish(batch(0, seeker_obs_->step));  // the seeker answers the step; the hider stays silent
  waitFor([] { return false; }, 0.3);                // what was already on its way arrives
  hider_batches = seeker_batches = 0;
  ASSERT_TRUE(waitFor([&] { return hider_batches >= 2; }, 10.0)) << "the silent hider's step was not re-sent";
  EXPECT_EQ(seeker_batches, 0) << "the seeker, which had answered, was sent the step again";
  EXPECT_EQ(hider_obs_->header.stamp, step->header.stamp) << "the step moved on without the hider";
  ASSERT_TRUE(playStep(0, 0));  // and the game plays on once the hider answers
}

TEST_F(WorldNodeTest, AnAnswerOvertakenByAResetIsDroppedWithoutAWarning) {
  // world/reset restarts arena 0 while both agents' answers to its step are on the way: they are
  // expected, so they are dropped and counted apart, not as wrong steps (which would warn).
  std::map<std::string, std::string> values;
  bool fresh = false;
  auto sub = nh_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10,
                                                             [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
                                                               for (const auto& s : m->status) {
                                                                 if (s.name != "hideseek world: input") continue;
                                                                 for (const auto& kv : s.values)
                                                                   values[kv.key] = kv.value;
                                                                 fresh = true;
                                                               }
                                                             });
  ASSERT_TRUE(waitFor([&] { return fresh; }, 5.0)) << "no /diagnostics from the world";
  const std::string wrong_steps = values["rejected_wrong_step"], dropped = values["dropped_superseded_by_reset"];
  ASSERT_EQ(dropped, "0");
  if (hider_obs_->step[0] == 0) ASSERT_TRUE(playStep(0, 0));  // step 0 would be awaited after the reset too
  const auto before = hider_obs_;
  const auto seeker_before = seeker_obs_;
  ASSERT_NE(before->seed[0], 11u);
  hideseek_msgs::Reset reset;
  reset.request.arena = 0;
  reset.request.seed = 11;
  ASSERT_TRUE(ros::service::call("world/reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  ASSERT_TRUE(waitFor([&] { return hider_obs_->seed[0] == 11u; }, 5.0)) << "no observation of the reset arena";
  EXPECT_EQ(hider_obs_->step[0], 0u);
  hider_pub_.publish(batch(0, before->step));  // arena 0: the step before the reset
  seeker_pub_.publish(batch(0, seeker_before->step));
  fresh = false;
  ASSERT_TRUE(waitFor([&] { return fresh && values["dropped_superseded_by_reset"] == "2"; }, 5.0))
      << "dropped_superseded_by_reset: " << values["dropped_superseded_by_reset"];
  EXPECT_EQ(values["rejected_wrong_step"], wrong_steps) << "an answer overtaken by a reset counted as a wrong step";
  // The same answer again, and another wrong step id, count as wrong steps.
  hider_pub_.publish(batch(0, before->step));
  auto wrong = batch(0, hider_obs_->step);
  wrong.step[0] += 7;
  hider_pub_.publish(wrong);
  fresh = false;
  ASSERT_TRUE(waitFor(
      [&] { return fresh && values["rejected_wrong_step"] == std::to_string(std::stoul(wrong_steps) + 2); }, 5.0))
      << "rejected_wrong_step " << values["rejected_wrong_step"] << ", before " << wrong_steps;
  EXPECT_EQ(values["dropped_superseded_by_reset"], "2");
  // And the reset arena plays on.
  ASSERT_TRUE(playStep(0, 0));
  EXPECT_EQ(hider_obs_->step[0], 1u);
}

// A real-time world starts once both agents listen as well as publish. An agent connects its
// action and observation topics one after the other; a world that started on the first would play
// step 0 before the agent could see it, and warn that the agent stood still.
// (realtime_start.test: a real-time world of its own, on the wall clock.)
TEST(RealtimeStart, TheWorldWaitsUntilEachAgentAndEachRequiredRecorderListens) {
  // realtime_start.test's world wants one listener of world/steps and one of world/episodes, as
  // record:=true asks for its recorder.
  ros::NodeHandle nh;
  int seeker_batches = 0;
  std::vector<uint32_t> hider_steps;
  std::vector<uint64_t> decisions;
  ros::Subscriber seeker_sub = nh.subscribe<hideseek_msgs::SeekerObservationBatch>(
      "seeker/observations", 10, [&](const hideseek_msgs::SeekerObservationBatch::ConstPtr&) { ++seeker_batches; });
  ros::Publisher hider_pub = nh.advertise<hideseek_msgs::ActionBatch>("hider/actions", 1);
  ros::Publisher seeker_pub = nh.advertise<hideseek_msgs::ActionBatch>("seeker/actions", 1);
  // Both agents publish and the seeker listens; the hider does not listen yet.
  ASSERT_TRUE(waitFor(
      [&] {
        return hider_pub.getNumSubscribers() > 0 && seeker_pub.getNumSubscribers() > 0 &&
               seeker_sub.getNumPublishers() > 0;
      },
      30.0))
      << "the real-time world did not connect";
  waitFor([] { return false; }, 1.5);
  EXPECT_EQ(seeker_batches, 0) << "the world started before the hider listened";
  // Both agents listen; neither recorder does yet.
  ros::Subscriber hider_sub = nh.subscribe<hideseek_msgs::ObservationBatch>(
      "hider/observations", 10,
      [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) { hider_steps.push_back(m->step[0]); });
  ASSERT_TRUE(waitFor([&] { return hider_sub.getNumPublishers() > 0; }, 30.0));
  waitFor([] { return false; }, 1.5);
  EXPECT_EQ(seeker_batches, 0) << "the world started before its step recorder listened";
  EXPECT_TRUE(hider_steps.empty()) << "the world started before its step recorder listened";
  // The step recorder listens; the episode recorder does not yet.
  ros::Subscriber steps_sub = nh.subscribe<hideseek_msgs::StepBatch>(
      "world/steps", 100, [&](const hideseek_msgs::StepBatch::ConstPtr& m) { decisions.push_back(m->decision); });
  ASSERT_TRUE(waitFor([&] { return steps_sub.getNumPublishers() > 0; }, 30.0));
  waitFor([] { return false; }, 1.5);
  EXPECT_TRUE(hider_steps.empty()) << "the world started before its episode recorder listened";
  int episodes = 0;
  ros::Subscriber episodes_sub = nh.subscribe<hideseek_msgs::EpisodeResult>(
      "world/episodes", 10, [&](const hideseek_msgs::EpisodeResult::ConstPtr&) { ++episodes; });
  ASSERT_TRUE(waitFor([&] { return !hider_steps.empty() && !decisions.empty(); }, 30.0))
      << "no observation and step record once everyone listened";
  EXPECT_EQ(hider_steps.front(), 0u) << "step 0 was played before the hider could see it";
  EXPECT_EQ(decisions.front(), 0u) << "the recorder missed the game's first decisions";
  EXPECT_GT(seeker_batches, 0);
}

TEST_F(WorldNodeTest, BrokenConfigStopsTheNodeBeforeItPublishes) {
  ros::WallDuration(1.0).sleep();
  ros::master::V_TopicInfo topics;
  ASSERT_TRUE(ros::master::getTopics(topics));
  for (const auto& t : topics) EXPECT_NE(t.name.rfind("/broken/", 0), 0u) << "broken world published " << t.name;
  std::vector<std::string> nodes;
  ASSERT_TRUE(ros::master::getNodes(nodes));
  for (const auto& n : nodes) EXPECT_NE(n, "/broken/world") << "a world with a bad config must exit";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "world_node_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
