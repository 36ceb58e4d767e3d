// `treesketch --version`: the project version and the git revision of the build
// (cmake/build_info.cmake), or "unknown" when built outside a git checkout.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "cli_support.h"

namespace treesketch {
namespace {

TEST(CliVersion, PrintsTheVersionAndTheGitRevision) {
  std::string out;
  ASSERT_EQ(test::runCli("--version", &out), 0) << out;
  // `git describe --always --dirty`: an abbreviated hash, or TAG-N-gHASH once tags exist.
  const std::regex expected("treesketch " TREESKETCH_VERSION " \\(git ([0-9A-Za-z._-]+|unknown)\\)\n");
  EXPECT_TRUE(std::regex_match(out, expected)) << out;
}

}  // namespace
}  // namespace treesketch
