// A person plays the hider from a terminal: keys become actions, and the hider's camera image is
// drawn in the same terminal (two pixels per character cell, 24-bit colour), so the player sees
// exactly what a policy sees and nothing more. ROS-free; teleop_node wires it to the game.
#pragma once

#include <termios.h>

#include <cstdint>
#include <optional>
#include <string>

namespace hideseek_hider {

// What a key (or an arrow key's escape sequence) asks for.
struct TeleopCommand {
  std::optional<uint8_t> action;  // an ActionBatch value, when the key names one
  bool quit = false;
};

// Reads keys from a stream of terminal bytes: w/s/a/d or the arrow keys move and turn, space or x
// stops, q, Ctrl-C or Ctrl-D quits (raw mode delivers Ctrl-D as a byte, not as an end of file).
// Escape sequences may arrive split across reads.
class TeleopKeys {
 public:
  // Feeds bytes; returns the command of the last complete key among them, if any.
  TeleopCommand feed(const std::string& bytes);

 private:
  std::string pending_;  // an escape sequence not yet complete
};

// A terminal in raw mode (keys arrive one by one, unechoed, reads never block) for the object's
// lifetime, restored when it ends. ok() is false where `fd` is no terminal. `owns`: close fd at the
// end (a /dev/tty opened for the purpose, not stdin).
class RawTerminal {
 public:
  RawTerminal(int fd, bool owns);
  ~RawTerminal();
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;
  bool ok() const { return fd_ >= 0; }
  // The bytes typed since the last call; empty when none.
  std::string read();
  // The other end hung up (the xterm was closed, the ssh session ended): no key will come again.
  bool closed() const;
  void write(const std::string& s);

 private:
  int fd_ = -1;
  bool owns_ = false;
  termios saved_{};  // the terminal's settings before raw mode
};

// The hider's action while no key is held: the last key's action until `key_timeout` seconds
// without a key (terminal auto-repeat refreshes a held key), then STAY; a timeout of 0 keeps the
// last action until another key.
class TeleopAction {
 public:
  explicit TeleopAction(double key_timeout) : timeout_(key_timeout) {}
  void press(uint8_t action, double now_s);
  uint8_t current(double now_s) const;

 private:
  double timeout_;
  uint8_t action_ = 0;
  double pressed_at_ = 0.0;
};

// The image (rows top down, RGB8) as terminal text: each character cell shows two pixels, one
// above the other (upper half block, foreground and background colours). Starts at the top-left
// corner of the screen so that successive frames overwrite each other.
std::string renderHalfBlocks(const uint8_t* rgb, int height, int width);

}  // namespace hideseek_hider
