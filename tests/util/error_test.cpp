// Tests of util/error: the three error types carry their messages, are caught apart (the CLI maps
// them to distinct exit codes) and by their standard bases, and the position helpers' formats.
#include "treesketch/util/error.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace treesketch {
namespace {

/// Throws `e` and reports which of the catch sites a caller of the library would use took it.
template <class E>
std::string caughtAs(const E& e) {
  try {
    throw e;
  } catch (const InputError&) {
    return "input";
  } catch (const OutputError&) {
    return "output";
  } catch (const OptionsError&) {
    return "options";
  } catch (...) {
    return "other";
  }
}

TEST(Errors, CarryTheirMessages) {
  EXPECT_STREQ(InputError("a.ply:3: expected 3 numbers").what(), "a.ply:3: expected 3 numbers");
  EXPECT_STREQ(OutputError("out.obj: write failed").what(), "out.obj: write failed");
  EXPECT_STREQ(OptionsError("--ring must be >= 3").what(), "--ring must be >= 3");
  EXPECT_STREQ(InputError("").what(), "");
}

TEST(Errors, AreCaughtApartAndByTheirStandardBases) {
  EXPECT_EQ(caughtAs(InputError("x")), "input");
  EXPECT_EQ(caughtAs(OutputError("x")), "output");
  EXPECT_EQ(caughtAs(OptionsError("x")), "options");
  EXPECT_EQ(caughtAs(std::runtime_error("x")), "other");
  // Code that knows only the standard library still catches them, message intact.
  try {
    throw InputError("bad input");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "bad input");
  }
  try {
    throw OutputError("bad output");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "bad output");
  }
  try {
    throw OptionsError("bad option");
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "bad option");
  }
}

TEST(Errors, PositionMessages) {
  EXPECT_EQ(atLine("trees/a.xyz", 12, "expected 3 numbers"), "trees/a.xyz:12: expected 3 numbers");
  EXPECT_EQ(atLine("a.obj", 1, "f: index 0"), "a.obj:1: f: index 0");
  EXPECT_EQ(atOffset("scan.las", 227, "truncated header"), "scan.las: byte offset 227: truncated header");
  // Offsets beyond 4 GiB are printed in full (a large LAS file).
  EXPECT_EQ(atOffset("big.las", 5'000'000'123ull, "truncated point"),
            "big.las: byte offset 5000000123: truncated point");
  EXPECT_STREQ(InputError(atLine("s.json", 4, "node 3: cycle")).what(), "s.json:4: node 3: cycle");
}

}  // namespace
}  // namespace treesketch
