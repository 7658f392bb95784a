// Fuzz target: the world's handling of an ActionBatch, serialized message bytes in (issue #49):
// the checked parse the world node subscribes through (CheckedActionBatch), the arena-count check,
// then every action offered to a two-arena game loop as the node offers it, and a decision taken
// when one is ready. No crash, hang or allocation beyond what the bytes hold.
#include <cstdint>
#include <memory>

#include "hideseek_game/checked_action_batch.h"
#include "hideseek_game/game_loop.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"

namespace {

hideseek_game::GameLoop& game() {
  static std::unique_ptr<hideseek_game::GameLoop> loop = [] {
    const auto v = hideseek_game::loadVariantConfig(HIDESEEK_CONFIG_DIR "/game.yaml",
                                                    HIDESEEK_CONFIG_DIR "/variants/stochasticmaps.yaml");
    hideseek_game::GameLoopOptions o;
    o.num_arenas = 2;
    o.render = false;
    return std::make_unique<hideseek_game::GameLoop>(
        v.game, std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file)), o);
  }();
  return *loop;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hideseek_msgs::ActionBatch msg;
  if (!hideseek_game::parseActionBatch(data, size, hideseek_game::kMaxArenas, &msg).empty()) return 0;
  hideseek_game::GameLoop& g = game();
  if (!hideseek_game::checkActionBatchSize(msg, 2).empty()) return 0;
  // The header's sequence number picks the agent; the world node knows it from the topic.
  const auto player = msg.header.seq % 2 ? hideseek_game::Player::kSeeker : hideseek_game::Player::kHider;
  for (int i = 0; i < 2; ++i) g.offer(player, i, msg.actions[i], msg.step[i]);
  if (g.decisionReady()) {
    g.takeDecision();
    g.playToNextDecision();  // to the step's end, or to the seeker's next decision inside it
  }
  return 0;
}
