// Text helpers shared by the parsers of names (options, views, keys, file extensions).
#pragma once

#include <string>

namespace treesketch {

/// `s` with its ASCII letters in lower case (other bytes unchanged), so that names and file
/// extensions compare without regard to case.
std::string lowercase(std::string s);

}  // namespace treesketch
