// Helpers for the io tests: checking InputError messages, building LAS and PLY bytes in code.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "treesketch/util/error.h"

namespace treesketch::io::testing {

/// Runs `f`, expects an exception of type E whose message contains every one of `parts`.
template <class E = InputError, class F>
void expectError(F&& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "expected an exception, none was thrown";
  } catch (const E& e) {
    std::string msg = e.what();
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "message: " << msg << "\nmissing: " << p;
  }
}

/// Feeds `read` every truncation of `bytes` (up to `maxTruncations`, evenly spread) and
/// `mutations` copies with a few random bytes changed (fixed seed). Each call must either return
/// or throw InputError; anything else (a crash, another exception type) fails the test. Run under
/// ASan this also checks that no reader reads out of bounds.
inline void expectOnlyInputErrors(const std::string& bytes, const std::function<void(const std::string&)>& read,
                                  int mutations = 300, std::size_t maxTruncations = 200) {
  auto tryOne = [&](const std::string& b, const std::string& what) {
    try {
      read(b);
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << what << ": unexpected exception " << e.what();
    }
  };
  std::size_t step = std::max<std::size_t>(1, bytes.size() / maxTruncations);
  for (std::size_t n = 0; n < bytes.size(); n += step) tryOne(bytes.substr(0, n), "truncated at " + std::to_string(n));
  std::mt19937 rng(1234);
  const char kSpecial[] = {'\0', '\n', ' ', '-', '9', 'e', '\xff', '/', '.', 'n'};
  for (int i = 0; i < mutations; ++i) {
    std::string b = bytes;
    int changes = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < changes && !b.empty(); ++k) {
      std::size_t at = rng() % b.size();
      b[at] = (rng() % 2) ? static_cast<char>(rng() & 0xff) : kSpecial[rng() % sizeof(kSpecial)];
    }
    tryOne(b, "mutation " + std::to_string(i));
  }
}

/// Appends `v` in little (big = false) or big endian byte order.
template <class T>
void put(std::string& s, T v, bool big = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big != (std::endian::native == std::endian::big)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  s.append(b, sizeof(T));
}

/// A tiny LAS writer for tests: the public header block and records whose first 12 bytes are
/// X, Y, Z int32 (the rest filled with a byte pattern, no record withheld).
struct LasSpec {
  int versionMinor = 2;
  int pointFormat = 0;
  int recordLength = 0;  ///< 0: the minimum for the format
  std::array<double, 3> scale{0.001, 0.001, 0.001};
  std::array<double, 3> offset{0, 0, 0};
  std::vector<std::array<std::int32_t, 3>> points;
  std::int64_t legacyCount = -1;  ///< -1: points.size() (0 for formats 6-10 in 1.4)
  std::int64_t count64 = -1;      ///< -1: points.size()
  int vlrBytes = 0;               ///< bytes of (junk) VLR area between header and points
  int headerSizeOverride = 0;
};

inline std::string buildLas(const LasSpec& s) {
  static const int kMin[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  int recLen = s.recordLength ? s.recordLength : kMin[s.pointFormat];
  int headerSize = s.versionMinor >= 4 ? 375 : s.versionMinor == 3 ? 235 : 227;
  int declaredHeader = s.headerSizeOverride ? s.headerSizeOverride : headerSize;
  std::string h = "LASF";
  put<std::uint16_t>(h, 0);  // file source id
  put<std::uint16_t>(h, 0);  // global encoding
  h.append(16, '\0');        // GUID
  h += static_cast<char>(1);
  h += static_cast<char>(s.versionMinor);
  std::string sys = "treesketch test";
  sys.resize(32, '\0');
  h += sys;
  std::string sw = "io_test_util";
  sw.resize(32, '\0');
  h += sw;
  put<std::uint16_t>(h, 1);
  put<std::uint16_t>(h, 2024);
  put<std::uint16_t>(h, static_cast<std::uint16_t>(declaredHeader));
  put<std::uint32_t>(h, static_cast<std::uint32_t>(headerSize + s.vlrBytes));
  put<std::uint32_t>(h, s.vlrBytes ? 1 : 0);
  h += static_cast<char>(s.pointFormat);
  put<std::uint16_t>(h, static_cast<std::uint16_t>(recLen));
  std::int64_t legacy = s.legacyCount >= 0                            ? s.legacyCount
                        : (s.versionMinor >= 4 && s.pointFormat >= 6) ? 0
                                                                      : static_cast<std::int64_t>(s.points.size());
  put<std::uint32_t>(h, static_cast<std::uint32_t>(legacy));
  for (int i = 0; i < 5; ++i) put<std::uint32_t>(h, 0);
  for (double v : s.scale) put(h, v);
  for (double v : s.offset) put(h, v);
  std::array<double, 3> mn{1e300, 1e300, 1e300}, mx{-1e300, -1e300, -1e300};
  for (const auto& p : s.points) {
    for (int k = 0; k < 3; ++k) {
      double w = p[k] * s.scale[k] + s.offset[k];
      mn[k] = std::min(mn[k], w);
      mx[k] = std::max(mx[k], w);
    }
  }
  for (int k = 0; k < 3; ++k) {
    put(h, mx[k]);
    put(h, mn[k]);
  }
  if (s.versionMinor >= 3) put<std::uint64_t>(h, 0);  // waveform start
  if (s.versionMinor >= 4) {
    put<std::uint64_t>(h, 0);  // first EVLR
    put<std::uint32_t>(h, 0);  // number of EVLRs
    put<std::uint64_t>(
        h, static_cast<std::uint64_t>(s.count64 >= 0 ? s.count64 : static_cast<std::int64_t>(s.points.size())));
    for (int i = 0; i < 15; ++i) put<std::uint64_t>(h, 0);
  }
  h.resize(static_cast<std::size_t>(headerSize), '\0');
  h.append(static_cast<std::size_t>(s.vlrBytes), '\x5a');
  for (const auto& p : s.points) {
    for (int k = 0; k < 3; ++k) put(h, p[k]);
    // Byte 15 carries no withheld flag (bit 7 in formats 0-5, bit 2 in 6-10): a test that wants
    // one sets it.
    for (int b = 12; b < recLen; ++b) h += static_cast<char>(b == 15 ? (0xA0 + b) & 0x7B : 0xA0 + b);
  }
  return h;
}

/// The classification flags of a LAS record (LAS 1.4 R15): synthetic, key-point, withheld and
/// (formats 6-10 only) overlap.
inline constexpr std::uint8_t kLasSynthetic = 1, kLasKeyPoint = 2, kLasWithheld = 4, kLasOverlap = 8;

/// Byte offset of record `i` in buildLas(s).
inline std::size_t lasRecordAt(const LasSpec& s, std::size_t i) {
  static const int kMin[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  const std::size_t header = s.versionMinor >= 4 ? 375 : s.versionMinor == 3 ? 235 : 227;
  const auto recLen = static_cast<std::size_t>(s.recordLength ? s.recordLength : kMin[s.pointFormat]);
  return header + static_cast<std::size_t>(s.vlrBytes) + i * recLen;
}

/// Sets the class and the classification flags (kLas*) of record `i` in `las` = buildLas(s):
/// formats 0-5 keep the class in the low five bits of byte 15 and synthetic, key-point, withheld
/// in bits 5-7; formats 6-10 the flags in the low four bits of byte 15 (the rest kept) and the
/// class in byte 16.
inline void setLasClass(std::string& las, const LasSpec& s, std::size_t i, std::uint8_t cls, std::uint8_t flags = 0) {
  const std::size_t at = lasRecordAt(s, i);
  if (s.pointFormat >= 6) {
    las[at + 15] = static_cast<char>((static_cast<std::uint8_t>(las[at + 15]) & 0xF0) | (flags & 0x0F));
    las[at + 16] = static_cast<char>(cls);
  } else {
    las[at + 15] = static_cast<char>((cls & 0x1F) | ((flags & 0x07) << 5));
  }
}

}  // namespace treesketch::io::testing
