#include "hideseek_hider/teleop.h"

#include <poll.h>
#include <unistd.h>

namespace hideseek_hider {

namespace {

// ActionBatch values (hideseek_msgs/ActionBatch.msg).
constexpr uint8_t kStay = 0, kForward = 1, kBackward = 2, kTurnLeft = 3, kTurnRight = 4;

std::optional<uint8_t> letterAction(char c) {
  switch (c) {
    case 'w':
    case 'W':
      return kForward;
    case 's':
    case 'S':
      return kBackward;
    case 'a':
    case 'A':
      return kTurnLeft;
    case 'd':
    case 'D':
      return kTurnRight;
    case ' ':
    case 'x':
    case 'X':
      return kStay;
    default:
      return std::nullopt;
  }
}

std::optional<uint8_t> arrowAction(char c) {
  switch (c) {
    case 'A':
      return kForward;
    case 'B':
      return kBackward;
    case 'D':
      return kTurnLeft;
    case 'C':
      return kTurnRight;
    default:
      return std::nullopt;
  }
}

}  // namespace

TeleopCommand TeleopKeys::feed(const std::string& bytes) {
  TeleopCommand out;
  for (char c : bytes) {
    if (!pending_.empty()) {
      if (pending_.size() == 1 && c != '[' && c != 'O') {
        pending_.clear();  // a lone Esc: the byte after it is a key of its own
      } else {
        pending_ += c;
        // An escape sequence ends at its final byte (0x40-0x7e): the arrows are ESC [ A..D or
        // ESC O A..D; a modified arrow (ESC [ 1 ; 5 A) counts as the arrow itself.
        if (pending_.size() > 2 && c >= 0x40 && c <= 0x7e) {
          if (auto a = arrowAction(c)) out.action = a;
          pending_.clear();
        } else if (pending_.size() > 16) {
          pending_.clear();  // not a sequence we know
        }
        continue;
      }
    }
    if (c == '\x1b') {
      pending_ = c;
    } else if (c == 'q' || c == 'Q' || c == '\x03' || c == '\x04') {
      out.quit = true;
    } else if (auto a = letterAction(c)) {
      out.action = a;
    }
  }
  return out;
}

RawTerminal::RawTerminal(int fd, bool owns) : owns_(owns) {
  if (fd < 0 || !isatty(fd) || tcgetattr(fd, &saved_) != 0) {
    if (fd >= 0 && owns) close(fd);
    return;
  }
  fd_ = fd;
  termios raw = saved_;
  raw.c_lflag &= ~(ICANON | ECHO);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  tcsetattr(fd_, TCSANOW, &raw);
  write("\x1b[2J\x1b[?25l");  // clear, hide the cursor
}

RawTerminal::~RawTerminal() {
  if (fd_ < 0) return;
  write("\x1b[0m\x1b[?25h\r\n");
  tcsetattr(fd_, TCSANOW, &saved_);
  if (owns_) close(fd_);
}

std::string RawTerminal::read() {
  std::string out;
  if (fd_ < 0) return out;
  char buf[64];
  ssize_t n;
  while ((n = ::read(fd_, buf, sizeof buf)) > 0) out.append(buf, static_cast<size_t>(n));
  return out;
}

bool RawTerminal::closed() const {
  if (fd_ < 0) return true;
  pollfd p{fd_, POLLIN, 0};
  return poll(&p, 1, 0) > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0;
}

void RawTerminal::write(const std::string& s) {
  if (fd_ < 0 || ::write(fd_, s.data(), s.size()) < 0) return;  // a closed terminal: nothing to show
}

void TeleopAction::press(uint8_t action, double now_s) {
  action_ = action;
  pressed_at_ = now_s;
}

uint8_t TeleopAction::current(double now_s) const {
  if (timeout_ > 0.0 && now_s - pressed_at_ > timeout_) return kStay;
  return action_;
}

std::string renderHalfBlocks(const uint8_t* rgb, int height, int width) {
  std::string out = "\x1b[H";
  out.reserve(static_cast<size_t>(height / 2 + 1) * width * 40);
  auto colour = [&](int layer, const uint8_t* p) {
    out += "\x1b[" + std::to_string(layer) + ";2;" + std::to_string(p[0]) + ';' + std::to_string(p[1]) + ';' +
           std::to_string(p[2]) + 'm';
  };
  for (int y = 0; y < height; y += 2) {
    for (int x = 0; x < width; ++x) {
      colour(38, rgb + (static_cast<size_t>(y) * width + x) * 3);
      colour(48, rgb + (static_cast<size_t>(y + 1 < height ? y + 1 : y) * width + x) * 3);
      out += "\u2580";
    }
    out += "\x1b[0m\r\n";
  }
  return out;
}

}  // namespace hideseek_hider
