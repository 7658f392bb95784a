#include "hideseek_game/learner_node_main.h"
#include "hideseek_seeker/seeker_node.h"

int main(int argc, char** argv) {
  return hideseek_game::learnerNodeMain<hideseek_seeker::SeekerNode>(argc, argv, "seeker");
}
