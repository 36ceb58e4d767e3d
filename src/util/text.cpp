// Text helpers (see text.h).
#include "treesketch/util/text.h"

#include <cctype>

namespace treesketch {

std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace treesketch
