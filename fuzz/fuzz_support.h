// Shared helpers of the fuzz harnesses (fuzz/*_fuzz.cpp): each harness defines one
// LLVMFuzzerTestOneInput and is built two ways — with clang and libFuzzer for `make fuzz`, and
// with the project's compiler and fuzz/replay_main.cpp as a CTest smoke test. A harness reports a
// failure by aborting (FUZZ_CHECK), which both drivers record as a crash with the message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::fuzz {

/// Prints "fuzz check failed: <what> (<file>:<line>)" on stderr and aborts (never returns).
[[noreturn]] void fail(const char* file, int line, const std::string& what);

#define FUZZ_CHECK(cond, what)                                         \
  do {                                                                 \
    if (!(cond)) ::treesketch::fuzz::fail(__FILE__, __LINE__, (what)); \
  } while (0)

/// The input as bytes of text (no copy).
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Writes `bytes` to a temporary file of this process whose name ends in `extension` (".ply",
/// "" for none) and returns its path; the next call with the same extension overwrites it. For
/// readers that only take a path. The files are removed when the process exits normally.
std::filesystem::path writeTempFile(std::string_view extension, std::string_view bytes);

/// Aborts unless every position (and scanner position) is finite, the attribute arrays are empty
/// or one per point, and there are at least `minPoints` points.
void checkCloud(const geom::PointCloud& cloud, std::size_t minPoints);
/// Aborts unless every vertex is finite, every index is in range, there is at least one
/// triangle, and colours/quality are empty or one per vertex.
void checkMesh(const geom::TriMesh& mesh);
/// Aborts unless the two clouds' positions and attributes are bit-identical.
void checkSameCloud(const geom::PointCloud& a, const geom::PointCloud& b, const char* what);

/// Aborts unless the two sketches are the same: up axis, defaults, cameras, and per node its id,
/// parent, children order, kind, screen/point/normal, params and kept circle (doubles bit for bit).
void checkSameSketch(const sketch::Sketch& a, const sketch::Sketch& b, const char* what);

/// Reads fixed-size values from the front of a fuzz input; past the end every value is zero.
class ByteSource {
 public:
  ByteSource(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::size_t remaining() const { return size_ - pos_; }
  template <class T>
  T next() {
    T value{};
    const std::size_t n = sizeof(T) < remaining() ? sizeof(T) : remaining();
    std::memcpy(&value, data_ + pos_, n);
    pos_ += n;
    return value;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// A double decoded from the input, biased towards hostile values: small multiples of 1/16, a
/// 16-bit mantissa times 10^e for any e in [-330, 310] (tiny, subnormal, huge, DBL_MAX-ish), and
/// raw 8-byte doubles. Non-finite results are replaced by 0 unless `allowNonFinite`.
double nextDouble(ByteSource& in, bool allowNonFinite = false);

}  // namespace treesketch::fuzz
