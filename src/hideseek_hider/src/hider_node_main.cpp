#include "hideseek_game/learner_node_main.h"
#include "hideseek_hider/hider_node.h"

int main(int argc, char** argv) {
  return hideseek_game::learnerNodeMain<hideseek_hider::HiderNode>(argc, argv, "hider");
}
