// Internal helpers of the io module: whole-stream reads, number parsing with std::from_chars,
// shortest exact number formatting, little/big-endian loads and stores.
#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <istream>
#include <string>
#include <string_view>
#include <type_traits>

namespace treesketch::io::detail {

/// Reads everything left in `in` (sized by seek when possible, else in 1 MiB blocks). Throws
/// InputError naming `source` if the stream is bad or a read fails.
std::string readAll(std::istream& in, const std::string& source);
/// Opens and reads a whole file; InputError if it does not exist, is a directory or unreadable.
std::string readFile(const std::filesystem::path& path);
/// Lower-case extension with the dot (".ply"), empty when none.
std::string lowerExtension(const std::filesystem::path& path);
/// A short printable rendering of `s` for messages (at most ~40 chars, control bytes escaped).
std::string quoted(std::string_view s);

/// Parses the whole of [b, e) as a double (a leading '+' is allowed). False if it is not a
/// number or out of range. NaN and Inf parse (callers reject them where needed).
inline bool parseDouble(const char* b, const char* e, double& out) {
  if (b < e && *b == '+') ++b;
  if (b == e) return false;
  auto r = std::from_chars(b, e, out);
  return r.ec == std::errc() && r.ptr == e;
}

/// Appends the shortest decimal that reads back to exactly `v`.
inline void appendNumber(std::string& s, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}
inline void appendNumber(std::string& s, std::uint64_t v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

template <class T>
inline T byteSwap(T v) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  std::memcpy(&v, b, sizeof(T));
  return v;
}

/// Loads a T stored at `p` in little (bigEndian=false) or big endian byte order.
template <class T>
inline T load(const char* p, bool bigEndian) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) v = byteSwap(v);
  return v;
}
template <class T>
inline T loadLE(const char* p) {
  return load<T>(p, false);
}

/// Appends `v` in little-endian byte order.
template <class T>
inline void storeLE(std::string& s, T v) {
  if constexpr (std::endian::native == std::endian::big) v = byteSwap(v);
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

}  // namespace treesketch::io::detail
