// Internal helpers of the io module: whole-stream reads, walking the lines of a text, buffered
// writes, number parsing with std::from_chars, shortest exact number formatting, little/big-endian
// loads and stores.
#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <istream>
#include <ostream>
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

/// The lines of a text in order: each next() gives the following line without its '\n' ('\r' is
/// kept: each format decides) and counts it, so number() is the 1-based number of the line just
/// given. A last line without '\n' counts; nothing follows a final '\n'.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  /// False (and `line` untouched) when the text is used up.
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t nl = text_.find('\n', pos_);
    const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
    line = text_.substr(pos_, end - pos_);
    pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
    ++number_;
    return true;
  }
  std::size_t number() const { return number_; }
  /// Byte offset of the first byte after the line just given (and its '\n').
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

/// Writers build their output in a string and hand it to the stream in blocks of about this many
/// bytes (one write per block instead of one per value; the bytes written are the same).
constexpr std::size_t kWriteBlock = std::size_t(1) << 20;

/// Writes `buf` to `out` and empties it once it holds kWriteBlock bytes or more (call after each
/// record; write what is left at the end with writeAll).
inline void flushIfFull(std::ostream& out, std::string& buf) {
  if (buf.size() < kWriteBlock) return;
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  buf.clear();
}
inline void writeAll(std::ostream& out, std::string& buf) {
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  buf.clear();
}

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
/// Appends "x y z", each the shortest decimal that reads back exactly (a point of a text format).
inline void appendXyz(std::string& s, double x, double y, double z) {
  appendNumber(s, x);
  s += ' ';
  appendNumber(s, y);
  s += ' ';
  appendNumber(s, z);
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
