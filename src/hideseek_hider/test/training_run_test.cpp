#include "hideseek_hider/training_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "hideseek_hider/checkpoint.h"
#include "shipped_ppo.h"

namespace hideseek_hider {

namespace {

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// Column `i` of a CSV row.
std::string column(const std::string& row, int i) {
  std::stringstream s(row);
  std::string cell;
  for (int c = 0; c <= i; ++c) std::getline(s, cell, ',');
  return cell;
}

constexpr int kArenas = 2;
constexpr int kSize = 36;

PpoOptions tinyPpo() {
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 4;  // a rollout is 2 arenas x 4 steps = 8 samples
  o.minibatches = 2;
  o.epochs = 1;
  return o;
}

TrainingOptions tinyRun(const std::string& dir, int64_t steps) {
  TrainingOptions o;
  o.output_dir = dir;
  o.total_steps = steps;
  o.checkpoint_interval_s = 1e9;  // the test decides when to checkpoint
  o.variant = "basic";
  o.image_height = kSize;
  o.image_width = kSize;
  return o;
}

// A run folder without an earlier test's checkpoint and log, the generator seeded as every run here.
std::string freshRun(const std::string& name) {
  const std::string dir = testing::TempDir() + name;
  std::remove((dir + "/checkpoint.pt").c_str());
  std::remove((dir + "/training_log.csv").c_str());
  torch::manual_seed(0);
  return dir;
}

// Feeds batches until `updates` more updates have run; every `period`-th step ends both episodes.
void feed(TrainingRun& run, int updates, int period = 3) {
  const std::vector<uint8_t> images(kArenas * kSize * kSize * 3, 128);
  int done_updates = 0;
  for (int step = 0; done_updates < updates && !run.finished(); ++step) {
    const uint8_t end = step % period == period - 1;
    std::optional<UpdateReport> report;
    run.step(images.data(), std::vector<float>(kArenas, 0.001f), std::vector<uint8_t>(kArenas, end), &report);
    if (report) ++done_updates;
  }
}

}  // namespace

TEST(TrainingRun, StepCountIsRoundedUpToWholeRolloutsSoEverySampleIsTrained) {
  EXPECT_EQ(wholeRollouts(3000, 256), 3072);
  EXPECT_EQ(wholeRollouts(3072, 256), 3072);
  EXPECT_EQ(wholeRollouts(1, 1024), 1024);
  const std::string dir = freshRun("run_rounding");
  TrainingRun run(tinyRun(dir, 30), tinyPpo(), kArenas, torch::kCPU);
  EXPECT_EQ(run.totalSteps(), 32);
  feed(run, 100);
  ASSERT_TRUE(run.finished());
  run.saveCheckpoint();
  // The last logged update, the checkpoint and the run all say 32: nothing collected went untrained.
  const auto log = lines(run.logPath());
  ASSERT_EQ(log.size(), 1u + 4u);
  EXPECT_EQ(column(log.back(), 1), "32");
  EXPECT_EQ(readCheckpointInfo(run.checkpointPath()).steps, 32);
}

TEST(TrainingRun, LoopProfileSaysWhereTheTimeWentUpdateByUpdate) {
  const std::string dir = testing::TempDir() + "run_loop_profile";
  for (const char* f : {"/checkpoint.pt", "/training_log.csv", "/loop_profile.csv"}) std::remove((dir + f).c_str());
  torch::manual_seed(0);
  TrainingRun run(tinyRun(dir, 16), tinyPpo(), kArenas, torch::kCPU);
  // The world takes 20 ms per step: the profile must show it as waiting, not as the hider's work.
  const std::vector<uint8_t> images(kArenas * kSize * kSize * 3, 128);
  std::vector<UpdateReport> reports;
  for (int step = 0; !run.finished(); ++step) {
    if (step > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::optional<UpdateReport> report;
    run.step(images.data(), std::vector<float>(kArenas, 0.001f), std::vector<uint8_t>(kArenas, 0), &report);
    if (report) reports.push_back(*report);
  }
  ASSERT_EQ(reports.size(), 2u);
  const auto rows = lines(run.loopProfilePath());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "update,steps,wait_s,inference_s,update_s,other_s");
  // Update 2 followed 4 steps, each after a 20 ms wait; update 1 followed 4 too, the first not waited for.
  EXPECT_GE(reports[1].loop.wait_s, 4 * 0.019);
  EXPECT_GE(reports[0].loop.wait_s, 3 * 0.019);
  EXPECT_LT(reports[1].loop.wait_s, 4 * 0.019 + 0.5);
  for (size_t i = 0; i < reports.size(); ++i) {
    const LoopTimes& t = reports[i].loop;
    EXPECT_GT(t.inference_s, 0.0);
    EXPECT_GT(t.update_s, 0.0);
    EXPECT_GE(t.other_s, 0.0);
    EXPECT_EQ(column(rows[i + 1], 0), std::to_string(i + 1));
    EXPECT_EQ(column(rows[i + 1], 1), std::to_string(8 * (i + 1)));
    EXPECT_NEAR(std::stod(column(rows[i + 1], 2)), t.wait_s, 1e-4);
    EXPECT_NEAR(std::stod(column(rows[i + 1], 4)), t.update_s, 1e-4);
  }
  // Between the two updates' log rows the wall clock moved by what the profile accounts for.
  const auto log = lines(run.logPath());
  ASSERT_EQ(log.size(), 3u);
  EXPECT_NEAR(std::stod(column(log[2], 2)) - std::stod(column(log[1], 2)), reports[1].loop.total(), 0.01);
}

TEST(TrainingRun, ResumedLogContinuesWithoutDuplicatesAndKeepsWallTimeAndEpisodes) {
  const std::string dir = freshRun("run_resume");
  double wall_at_checkpoint = 0.0;
  int64_t episodes_at_checkpoint = 0;
  {
    TrainingRun run(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
    feed(run, 3);
    run.saveCheckpoint();  // at step 24
    const CheckpointInfo info = readCheckpointInfo(run.checkpointPath());
    EXPECT_EQ(info.steps, 24);
    wall_at_checkpoint = info.wall_s;
    episodes_at_checkpoint = info.episodes;
    EXPECT_GT(episodes_at_checkpoint, 0);
    feed(run, 2);  // logged, then lost: the process "dies" before the next checkpoint
    EXPECT_EQ(lines(run.logPath()).size(), 1u + 5u);
  }
  TrainingRun resumed(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
  EXPECT_TRUE(resumed.resumed());
  EXPECT_EQ(resumed.steps(), 24);
  EXPECT_EQ(resumed.droppedLogRows(), 2);
  feed(resumed, 2);
  const auto log = lines(resumed.logPath());
  ASSERT_EQ(log.size(), 1u + 5u);
  EXPECT_EQ(log[0].substr(0, 12), "update,steps");
  for (size_t i = 1; i < log.size(); ++i) {
    EXPECT_EQ(column(log[i], 0), std::to_string(i)) << "update numbers run 1..5 once each";
    EXPECT_EQ(column(log[i], 1), std::to_string(8 * i)) << "steps";
  }
  // Wall time and episodes continue from the checkpoint instead of restarting at 0.
  EXPECT_GE(std::stod(column(log[4], 2)), wall_at_checkpoint);
  EXPECT_GT(std::stoll(column(log[4], 4)), episodes_at_checkpoint);
  EXPECT_GE(std::stod(column(log[5], 2)), std::stod(column(log[4], 2)));
}

TEST(TrainingRun, AStopMidRolloutKeepsTheLastUpdateAndItsLogRow) {
  // Ctrl-C comes while a rollout is being recorded: the checkpoint holds the last update (its steps
  // and the wall time of its log row), not the samples of the unfinished rollout, and the next
  // start resumes there with every log row kept.
  const std::string dir = freshRun("run_stop");
  {
    TrainingRun run(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
    EXPECT_FALSE(run.saveCheckpointOnStop()) << "no update yet: nothing to keep";
    feed(run, 3);
    const std::vector<uint8_t> images(kArenas * kSize * kSize * 3, 128);
    std::optional<UpdateReport> report;
    for (int k = 0; k < 2; ++k) {  // half of the next rollout, in which both arenas' episodes end
      run.step(images.data(), std::vector<float>(kArenas, 0.001f), std::vector<uint8_t>(kArenas, 1), &report);
    }
    EXPECT_EQ(run.steps(), 24 + 2 * kArenas);
    EXPECT_EQ(run.updatedSteps(), 24);
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    const auto before_stop = std::filesystem::file_time_type::clock::now();
    ASSERT_TRUE(run.saveCheckpointOnStop());
    // Its file is dated at the update it holds, not at the stop: the sweep drops the pauses that
    // ended after a run's checkpoint, since a resumed run's log holds none of them.
    EXPECT_LT(std::filesystem::last_write_time(run.checkpointPath()), before_stop - std::chrono::milliseconds(30));
    EXPECT_FALSE(run.saveCheckpointOnStop()) << "the checkpoint holds the last update already";
    const CheckpointInfo info = readCheckpointInfo(run.checkpointPath());
    EXPECT_EQ(info.steps, 24);
    const auto log = lines(run.logPath());
    ASSERT_EQ(log.size(), 1u + 3u);
    // The log writes six significant digits.
    EXPECT_NEAR(std::stod(column(log[3], 2)), info.wall_s, 1e-5 * std::max(1.0, info.wall_s))
        << "the wall time of the update's log row";
  }
  // The episode window it keeps is the update's too: the same run checkpointed at that update.
  const std::string reference = freshRun("run_stop_reference");
  {
    TrainingRun run(tinyRun(reference, 80), tinyPpo(), kArenas, torch::kCPU);
    feed(run, 3);
    run.saveCheckpoint();
  }
  const CheckpointInfo at_update = readCheckpointInfo(reference + "/checkpoint.pt");
  const CheckpointInfo at_stop = readCheckpointInfo(dir + "/checkpoint.pt");
  EXPECT_EQ(at_stop.episodes, at_update.episodes);
  EXPECT_EQ(at_stop.recent_lengths, at_update.recent_lengths) << "episodes of the unfinished rollout kept";
  TrainingRun resumed(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
  EXPECT_TRUE(resumed.resumed());
  EXPECT_EQ(resumed.steps(), 24);
  EXPECT_EQ(resumed.droppedLogRows(), 0);
  EXPECT_FALSE(resumed.saveCheckpointOnStop()) << "resumed, no update since: nothing new to keep";
}

TEST(TrainingRun, ACheckpointRecordsItsGameAndIsNotResumedUnderAnother) {
  const std::string dir = freshRun("run_game");
  TrainingOptions v3 = tinyRun(dir, 80);
  v3.game = "v3";
  {
    TrainingRun run(v3, tinyPpo(), kArenas, torch::kCPU);
    feed(run, 1);
    run.saveCheckpoint();
    EXPECT_EQ(readCheckpointInfo(run.checkpointPath()).game, "v3");
  }
  try {
    TrainingRun wrong(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);  // game v2
    FAIL() << "a v3 checkpoint was resumed as v2";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("was trained on game v3; this run's game is v2"), std::string::npos) << what;
  }
  TrainingRun same(v3, tinyPpo(), kArenas, torch::kCPU);
  EXPECT_TRUE(same.resumed());
  EXPECT_EQ(same.steps(), 8);
}

TEST(TrainingRun, ACheckpointIsNotResumedUnderAnotherVariant) {
  // train.launch variant:=fasterhider output_dir:=<a basic run's folder> trained on, and the
  // checkpoint then called the whole run fasterhider.
  const std::string dir = freshRun("run_variant");
  {
    TrainingRun run(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);  // basic
    feed(run, 1);
    run.saveCheckpoint();
  }
  TrainingOptions faster = tinyRun(dir, 80);
  faster.variant = "fasterhider";
  try {
    TrainingRun wrong(faster, tinyPpo(), kArenas, torch::kCPU);
    FAIL() << "a basic checkpoint was resumed as fasterhider";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("was trained on variant 'basic'; this run's variant is 'fasterhider'"), std::string::npos)
        << what;
  }
  EXPECT_EQ(readCheckpointInfo(dir + "/checkpoint.pt").variant, "basic");
  EXPECT_EQ(lines(dir + "/training_log.csv").size(), 2u);  // the header and the one update: untouched
  TrainingRun same(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
  EXPECT_TRUE(same.resumed());
}

TEST(TrainingRun, TheOutputFolderIsCreatedWithItsParents) {
  // The default output folder (~/.ros/hideseek_runs/VARIANT) and a user's ~/runs/basic need
  // parents that a fresh machine does not have.
  const std::string root = testing::TempDir() + "run_nested";
  std::filesystem::remove_all(root);
  torch::manual_seed(0);
  TrainingRun run(tinyRun(root + "/a/b", 16), tinyPpo(), kArenas, torch::kCPU);
  feed(run, 1);
  run.saveCheckpoint();
  EXPECT_TRUE(std::filesystem::is_regular_file(root + "/a/b/checkpoint.pt"));
  EXPECT_TRUE(std::filesystem::is_regular_file(root + "/a/b/training_log.csv"));
}

TEST(TrainingRun, ResumedLogAveragesOverTheEpisodesBeforeTheCheckpointToo) {
  const std::string dir = freshRun("run_resume_window");
  {
    TrainingRun run(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
    // Episodes end at steps 4 and 9 (the first step only acts): lengths 4 and 5 in both arenas.
    feed(run, 3, 5);
    run.saveCheckpoint();
    const CheckpointInfo info = readCheckpointInfo(run.checkpointPath());
    EXPECT_EQ(info.recent_lengths, (std::vector<int64_t>{4, 4, 5, 5}));
    ASSERT_EQ(info.recent_returns.size(), 4u);
    EXPECT_NEAR(info.recent_returns[3], 5 * 0.001, 1e-6);
  }
  TrainingRun resumed(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
  ASSERT_TRUE(resumed.resumed());
  // Short episodes after the resume (lengths 1 and 2) join the four before it: the average is
  // 3, where a window restarted at the resume would read 1.5, a dip the run never had.
  feed(resumed, 1, 2);
  const auto log = lines(resumed.logPath());
  ASSERT_EQ(log.size(), 1u + 4u);
  EXPECT_NEAR(std::stod(column(log.back(), 5)), 3.0, 1e-9);
  EXPECT_NEAR(std::stod(column(log.back(), 6)), 0.003, 1e-6);
}

TEST(TrainingRun, RestartAfterAKillBeforeTheFirstCheckpointStartsAFreshLog) {
  const std::string dir = freshRun("run_no_checkpoint");
  {
    TrainingRun run(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
    feed(run, 3);  // logged, never checkpointed
  }
  // A kill mid-write leaves half a row without its newline.
  std::ofstream(dir + "/training_log.csv", std::ios::app) << "4,32,0.1";
  TrainingRun restarted(tinyRun(dir, 80), tinyPpo(), kArenas, torch::kCPU);
  EXPECT_FALSE(restarted.resumed());
  EXPECT_EQ(restarted.droppedLogRows(), 4);
  feed(restarted, 2);
  const auto log = lines(restarted.logPath());
  ASSERT_EQ(log.size(), 1u + 2u);
  EXPECT_EQ(column(log[1], 0), "1");
  EXPECT_EQ(column(log[2], 1), "16");
}

TEST(TrainingLog, ARowCutOffMidWriteIsDropped) {
  const std::string path = testing::TempDir() + "cut_log.csv";
  std::ofstream(path) << "update,steps\n1,8\n2,16\n3,2";
  EXPECT_EQ(truncateLogAfter(path, 16), 1);
  EXPECT_EQ(lines(path), (std::vector<std::string>{"update,steps", "1,8", "2,16"}));
}

TEST(FormatDuration, ReadsAtEveryScale) {
  EXPECT_EQ(formatDuration(0.4), "0 s");
  EXPECT_EQ(formatDuration(42.2), "42 s");
  EXPECT_EQ(formatDuration(125), "2 min 05 s");
  EXPECT_EQ(formatDuration(3599), "59 min 59 s");
  EXPECT_EQ(formatDuration(3 * 3600 + 7 * 60 + 10), "3 h 07 min");
  EXPECT_EQ(formatDuration(-5), "0 s");
}

}  // namespace hideseek_hider
