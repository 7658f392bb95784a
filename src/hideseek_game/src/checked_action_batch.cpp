#include "hideseek_game/checked_action_batch.h"

#include "hideseek_game/wire_reader.h"

namespace hideseek_game {

std::string parseActionBatch(const uint8_t* data, size_t size, size_t max_arenas, hideseek_msgs::ActionBatch* out) {
  WireReader r(data, size);
  uint32_t seq = 0, sec = 0, nsec = 0, frame_len = 0;
  if (!r.u32(seq) || !r.u32(sec) || !r.u32(nsec) || !r.u32(frame_len)) return "truncated header";
  if (frame_len > r.left()) return "header frame_id longer than the message";
  if (frame_len > 256) return "header frame_id longer than 256 bytes";
  std::string frame(frame_len, '\0');
  r.bytes(frame.data(), frame_len);
  uint32_t n_actions = 0;
  if (!r.u32(n_actions)) return "truncated before actions";
  if (n_actions > r.left()) return "actions longer than the message";
  if (n_actions > max_arenas) return "more than " + std::to_string(max_arenas) + " actions";
  std::vector<uint8_t> actions(n_actions);
  r.bytes(actions.data(), n_actions);
  uint32_t n_steps = 0;
  if (!r.u32(n_steps)) return "truncated before step";
  if (n_steps > r.left() / 4) return "step longer than the message";
  if (n_steps > max_arenas) return "more than " + std::to_string(max_arenas) + " step ids";
  std::vector<uint32_t> steps(n_steps);
  r.bytes(steps.data(), 4 * static_cast<size_t>(n_steps));
  if (r.left() != 0) return std::to_string(r.left()) + " bytes after the message";
  out->header.seq = seq;
  out->header.stamp.sec = sec;
  out->header.stamp.nsec = nsec;
  out->header.frame_id = std::move(frame);
  out->actions = std::move(actions);
  out->step = std::move(steps);
  return "";
}

std::string checkActionBatchSize(const hideseek_msgs::ActionBatch& msg, size_t num_arenas) {
  if (msg.actions.size() == num_arenas && msg.step.size() == num_arenas) return "";
  return std::to_string(msg.actions.size()) + " actions and " + std::to_string(msg.step.size()) + " step ids for " +
         std::to_string(num_arenas) + " arenas";
}

}  // namespace hideseek_game
