// The shipped PPO options (config/ppo.yaml, their one source of defaults), for tests that change
// a few of them. HIDESEEK_CONFIG_DIR is the repository's config/ folder.
#pragma once

#include <string>

#include "hideseek_hider/ppo.h"

namespace hideseek_hider {
inline PpoOptions shippedPpoOptions() { return loadPpoOptions(std::string(HIDESEEK_CONFIG_DIR) + "/ppo.yaml"); }
}  // namespace hideseek_hider
