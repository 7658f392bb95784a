// Reads analysis recordings (hideseek_msgs/StepBatch, world/steps) with the C++ rosbag API.
#pragma once

#include <hideseek_msgs/StepBatch.h>

#include <string>

#include "hideseek_analysis/step_log.h"

namespace hideseek_analysis {

// One StepBatch as a DecisionRecord; throws std::invalid_argument naming the field whose length
// does not match num_arenas.
DecisionRecord toDecisionRecord(const hideseek_msgs::StepBatch& msg);

// Every StepBatch of the bag, whatever topic it was recorded on, in decision order. Throws
// MissingStepsError (prefixed with the bag's path) at the first hole, and std::runtime_error for
// a bag that cannot be opened, fails checkBagFile (cut, unindexed, malformed) or holds no StepBatch.
StepLog readStepBag(const std::string& path);

}  // namespace hideseek_analysis
