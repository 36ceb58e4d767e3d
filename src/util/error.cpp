#include "treesketch/util/error.h"

namespace treesketch {

std::string atLine(const std::string& source, std::size_t line, const std::string& what) {
  return source + ":" + std::to_string(line) + ": " + what;
}

std::string atOffset(const std::string& source, std::uint64_t offset, const std::string& what) {
  return source + ": byte offset " + std::to_string(offset) + ": " + what;
}

}  // namespace treesketch
