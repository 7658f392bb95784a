// An agent node's last answer, kept for the batch the world re-sends when an answer was lost: the
// same step gets the same answer, so a training run never takes one step twice and a sampled
// policy never answers one step two ways. A reset re-sends at the same sim time but with new step
// ids or seeds, and must be answered afresh (the kept answer's step ids would be rejected, and
// lockstep would wait for ever).
#pragma once

#include <hideseek_msgs/ActionBatch.h>
#include <ros/time.h>

#include <cstdint>
#include <vector>

namespace hideseek_game {

class ReplyCache {
 public:
  // The answer kept for the batch stamped `stamp` with these step ids and seeds; null when the
  // batch is not the one it answered (or nothing was answered yet).
  const hideseek_msgs::ActionBatch* find(const ros::Time& stamp, const std::vector<uint32_t>& step,
                                         const std::vector<uint32_t>& seed) const {
    if (answer_.actions.empty() || stamp != stamp_ || step != answer_.step || seed != seeds_) return nullptr;
    return &answer_;
  }
  // Keeps `answer` as the answer to the batch stamped `stamp` with these seeds (its step ids are
  // answer.step). An empty answer (training ended) is kept but never replayed.
  void keep(const ros::Time& stamp, const std::vector<uint32_t>& seed, const hideseek_msgs::ActionBatch& answer) {
    stamp_ = stamp;
    seeds_ = seed;
    answer_ = answer;
  }

 private:
  ros::Time stamp_;
  std::vector<uint32_t> seeds_;
  hideseek_msgs::ActionBatch answer_;
};

}  // namespace hideseek_game
