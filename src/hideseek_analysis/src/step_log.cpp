#include "hideseek_analysis/step_log.h"

namespace hideseek_analysis {

namespace {

std::string where(uint64_t decision, int arena) {
  return "decision " + std::to_string(decision) + ", arena " + std::to_string(arena);
}

}  // namespace

void StepLog::append(DecisionRecord d) {
  const int n = static_cast<int>(d.arenas.size());
  if (n == 0) throw std::invalid_argument("decision " + std::to_string(d.decision) + " holds no arena");
  if (!d.images.empty() &&
      (d.height <= 0 || d.width <= 0 || d.images.size() != static_cast<size_t>(n) * d.height * d.width * 3)) {
    throw std::invalid_argument("decision " + std::to_string(d.decision) + ": " + std::to_string(d.images.size()) +
                                " image bytes for " + std::to_string(n) + " arenas of " + std::to_string(d.height) +
                                "x" + std::to_string(d.width) + " RGB8");
  }
  if (decisions_ == 0) {
    num_arenas_ = n;
    first_decision_ = d.decision;
  } else {
    const uint64_t expected = first_decision_ + decisions_;
    if (d.decision != expected) {
      if (d.decision > expected) {
        throw MissingStepsError("decisions " + std::to_string(expected) + " to " + std::to_string(d.decision - 1) +
                                " are missing (" + std::to_string(d.decision - expected) + " decision steps of " +
                                std::to_string(num_arenas_) + " arenas)");
      }
      throw MissingStepsError("decision " + std::to_string(d.decision) + " comes after decision " +
                              std::to_string(expected - 1) + " (repeated or out of order)");
    }
    if (n != num_arenas_) {
      throw MissingStepsError("decision " + std::to_string(d.decision) + " has " + std::to_string(n) +
                              " arenas, the log " + std::to_string(num_arenas_));
    }
    const ArenaStepRecord* previous = &records_[records_.size() - num_arenas_];
    for (int i = 0; i < n; ++i) {
      const ArenaStepRecord& p = previous[i];
      const ArenaStepRecord& c = d.arenas[i];
      const bool continues = p.outcome == 0 ? (c.seed == p.seed && c.step == p.step + 1) : c.step == 0;
      if (!continues) {
        throw MissingStepsError(where(d.decision, i) + ": step " + std::to_string(c.step) + " of seed " +
                                std::to_string(c.seed) + " does not follow step " + std::to_string(p.step) +
                                " of seed " + std::to_string(p.seed) + (p.outcome ? " (which ended its episode)" : ""));
      }
    }
  }
  if (!d.images.empty()) {
    if (image_bytes_ == 0) {
      height_ = d.height;
      width_ = d.width;
      image_bytes_ = static_cast<size_t>(d.height) * d.width * 3;
    } else if (d.height != height_ || d.width != width_) {
      throw std::invalid_argument("decision " + std::to_string(d.decision) + ": images of " + std::to_string(d.height) +
                                  "x" + std::to_string(d.width) + ", earlier ones " + std::to_string(height_) + "x" +
                                  std::to_string(width_));
    }
  }
  const int64_t first_image = numImages();
  for (int i = 0; i < n; ++i) {
    ArenaStepRecord r = d.arenas[i];
    r.decision = d.decision;
    r.arena = i;
    r.image = d.images.empty() ? -1 : first_image + i;
    records_.push_back(r);
  }
  images_.insert(images_.end(), d.images.begin(), d.images.end());
  ++decisions_;
}

}  // namespace hideseek_analysis
