// The desktop tool's messages: every info and error posted by an action, the one the status bar
// shows now (an error until dismissed or replaced, an info for a few seconds), and when that will
// change by itself (so an idle window wakes up only then). Plain C++, no GL.
#pragma once

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace treesketch::viewer {

/// A status message for the status bar / log.
struct StatusMessage {
  bool error = false;
  std::string text;
  std::chrono::steady_clock::time_point time{};  ///< when it was posted
};

class StatusLog {
 public:
  /// `infoSeconds`: how long an info message stays in the status bar (ViewerOptions).
  explicit StatusLog(double infoSeconds = 6.0) : infoSeconds_(infoSeconds) {}

  void info(const std::string& text);
  void error(const std::string& text);
  const std::vector<StatusMessage>& messages() const { return messages_; }
  StatusMessage lastMessage() const { return messages_.empty() ? StatusMessage{} : messages_.back(); }
  std::size_t errorCount() const { return errorCount_; }
  /// What the status bar shows at `now`: the last message if it is an error not dismissed, or an
  /// info younger than the info time; nullopt otherwise (the bar shows counts).
  std::optional<StatusMessage> statusLine(std::chrono::steady_clock::time_point now) const;
  std::optional<StatusMessage> statusLine() const { return statusLine(std::chrono::steady_clock::now()); }
  /// Hides the status bar's message (Esc, or its close button); the log keeps it.
  void dismiss() { dismissed_ = true; }
  /// When the status line will change by itself next (an info expiring); nullopt when it will not.
  std::optional<std::chrono::steady_clock::time_point> expiry() const;

 private:
  double infoSeconds_;
  std::vector<StatusMessage> messages_;
  bool dismissed_ = false;
  std::size_t errorCount_ = 0;
};

}  // namespace treesketch::viewer
