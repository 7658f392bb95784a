// Every decision of every arena of an analysis rollout, checked for completeness as it is read:
// a log with a hole in it is refused, never analysed past the hole.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace hideseek_analysis {

// One arena's decision: the state it was in, what both agents chose, what the step gave.
struct ArenaStepRecord {
  uint64_t decision = 0;
  int arena = 0;
  uint32_t episode = 0;
  uint32_t seed = 0;  // unique per episode: the episode's name in every output
  uint32_t step = 0;
  double hider_x = 0, hider_y = 0, hider_yaw = 0;
  double seeker_x = 0, seeker_y = 0, seeker_yaw = 0;
  double distance = 0;
  bool hider_sees_seeker = false;  // S
  bool seeker_sees_hider = false;  // H
  bool obstacle_in_view = false;   // O
  int hider_action = 0;
  int seeker_action = 0;
  double reward = 0;
  int outcome = 0;     // 0 running, 1 captured, 2 survived (the step ended the episode so)
  int64_t image = -1;  // index of the hider image of this state in StepLog::images(), or -1
};

// One decision of every arena, as a reader hands it over.
struct DecisionRecord {
  uint64_t decision = 0;
  std::vector<ArenaStepRecord> arenas;  // arena i at index i
  int height = 0;
  int width = 0;
  std::vector<uint8_t> images;  // arenas.size() RGB8 images of height x width, or none
};

// Thrown when a decision does not follow the previous one: the rollout lost steps.
class MissingStepsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Decisions in order. append() refuses (MissingStepsError) a jump in the decision counter, a
// change of the arena count, and an arena whose step does not continue its episode (the next
// step of the same seed, or step 0 of a new seed after an outcome); std::invalid_argument for a
// record that is malformed in itself.
class StepLog {
 public:
  void append(DecisionRecord decision);

  int numArenas() const { return num_arenas_; }
  size_t decisions() const { return decisions_; }
  uint64_t firstDecision() const { return first_decision_; }
  const std::vector<ArenaStepRecord>& records() const { return records_; }  // decision-major
  const std::vector<uint8_t>& images() const { return images_; }
  int64_t numImages() const { return image_bytes_ ? static_cast<int64_t>(images_.size() / image_bytes_) : 0; }
  int imageHeight() const { return height_; }
  int imageWidth() const { return width_; }

 private:
  int num_arenas_ = 0;
  size_t decisions_ = 0;
  uint64_t first_decision_ = 0;
  int height_ = 0, width_ = 0;
  size_t image_bytes_ = 0;
  std::vector<ArenaStepRecord> records_;
  std::vector<uint8_t> images_;
};

}  // namespace hideseek_analysis
