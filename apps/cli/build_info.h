// What `treesketch --version` prints: the project version and the git revision of the build.
// The revision lives in one generated file (build_info.cpp in the build folder, rewritten only
// when `git describe` changes), so a new commit recompiles one file, not the CLI.
#pragma once

#include <string>

namespace treesketch::cli {

/// "treesketch 0.1.0 (git 469188e-dirty)"; "(git unknown)" when built outside a git checkout.
std::string versionString();

}  // namespace treesketch::cli
