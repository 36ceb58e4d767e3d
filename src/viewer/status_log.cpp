// StatusLog: the desktop tool's messages. See include/treesketch/viewer/status_log.h.
#include "treesketch/viewer/status_log.h"

namespace treesketch::viewer {

namespace {

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

void StatusLog::info(const std::string& text) {
  messages_.push_back(StatusMessage{false, text, std::chrono::steady_clock::now()});
  dismissed_ = false;
}

void StatusLog::error(const std::string& text) {
  messages_.push_back(StatusMessage{true, text, std::chrono::steady_clock::now()});
  dismissed_ = false;
  ++errorCount_;
}

std::optional<StatusMessage> StatusLog::statusLine(std::chrono::steady_clock::time_point now) const {
  if (messages_.empty() || dismissed_) return std::nullopt;
  const StatusMessage& last = messages_.back();
  if (last.error) return last;  // until dismissed or replaced by a newer message
  if (now - last.time < seconds(infoSeconds_)) return last;
  return std::nullopt;
}

std::optional<std::chrono::steady_clock::time_point> StatusLog::expiry() const {
  if (messages_.empty() || dismissed_ || messages_.back().error) return std::nullopt;
  return messages_.back().time + seconds(infoSeconds_);
}

}  // namespace treesketch::viewer
