// Classified clouds as PLY with two extra properties and as LAS 1.4 format 6 with an extra byte
// (io/classified_cloud.h).
#include "treesketch/io/classified_cloud.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "io/io_util.h"
#include "treesketch/io/ply.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::io {

namespace {

void checkArrays(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& codes, const std::vector<float>& p) {
  if (codes.size() != cloud.size() || p.size() != cloud.size())
    throw OptionsError("classified cloud: " + std::to_string(cloud.size()) + " points but " +
                       std::to_string(codes.size()) + " classes and " + std::to_string(p.size()) + " probabilities");
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (!cloud.positions[i].allFinite())
      throw OutputError("classified cloud: point " + std::to_string(i) + " has a non-finite coordinate");
}

void writePly(std::ostream& out, const geom::PointCloud& cloud, const std::vector<std::uint8_t>& codes,
              const std::vector<float>& p, const std::string& name) {
  std::string buf = "ply\nformat binary_little_endian 1.0\ncomment written by treesketch\n";
  if (cloud.up) buf += std::string("comment ") + kPlyUpKey + " " + geom::toString(*cloud.up) + "\n";
  buf += "element vertex " + std::to_string(cloud.size()) +
         "\nproperty double x\nproperty double y\nproperty double z\nproperty uchar classification\nproperty float " +
         name + "\nend_header\n";
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3& q = cloud.positions[i];
    detail::storeLE(buf, q.x());
    detail::storeLE(buf, q.y());
    detail::storeLE(buf, q.z());
    buf += static_cast<char>(codes[i]);
    detail::storeLE(buf, p[i]);
    detail::flushIfFull(out, buf);
  }
  detail::writeAll(out, buf);
}

void putText(std::string& s, const std::string& text, std::size_t width) {
  std::string t = text.substr(0, width);
  t.resize(width, '\0');
  s += t;
}

constexpr std::uint16_t kLasHeaderSize = 375;    // LAS 1.4
constexpr std::uint16_t kExtraBytesSize = 192;   // one Extra Bytes descriptor
constexpr std::uint16_t kRecordLength = 30 + 4;  // format 6 + one float

/// The public header block of LAS 1.4 with one VLR and `n` points of format 6.
std::string lasHeader(std::uint64_t n, const geom::Vec3& scale, const geom::Vec3& offset, const geom::BBox& box) {
  std::string s = "LASF";
  detail::storeLE<std::uint16_t>(s, 0);     // file source id
  detail::storeLE<std::uint16_t>(s, 0x10);  // global encoding: WKT (required for formats 6-10)
  s.append(16, '\0');                       // project GUID
  s += static_cast<char>(1);
  s += static_cast<char>(4);
  putText(s, "treesketch", 32);
  putText(s, "treesketch classify", 32);
  detail::storeLE<std::uint16_t>(s, 0);  // creation day
  detail::storeLE<std::uint16_t>(s, 0);  // creation year
  detail::storeLE<std::uint16_t>(s, kLasHeaderSize);
  detail::storeLE<std::uint32_t>(s, kLasHeaderSize + 54 + kExtraBytesSize);  // offset to point data
  detail::storeLE<std::uint32_t>(s, 1);                                      // VLRs
  s += static_cast<char>(6);
  detail::storeLE<std::uint16_t>(s, kRecordLength);
  s.append(4 + 20, '\0');  // legacy counts: 0 for formats 6-10
  for (int k = 0; k < 3; ++k) detail::storeLE(s, scale[k]);
  for (int k = 0; k < 3; ++k) detail::storeLE(s, offset[k]);
  for (int k = 0; k < 3; ++k) {
    detail::storeLE(s, box.max[k]);
    detail::storeLE(s, box.min[k]);
  }
  detail::storeLE<std::uint64_t>(s, 0);  // waveform
  detail::storeLE<std::uint64_t>(s, 0);  // first EVLR
  detail::storeLE<std::uint32_t>(s, 0);  // EVLRs
  detail::storeLE<std::uint64_t>(s, n);
  detail::storeLE<std::uint64_t>(s, n);  // all first returns
  s.append(14 * 8, '\0');
  return s;
}

/// The Extra Bytes VLR describing one float named `name`.
std::string extraBytesVlr(const std::string& name) {
  std::string s;
  detail::storeLE<std::uint16_t>(s, 0);
  putText(s, "LASF_Spec", 16);
  detail::storeLE<std::uint16_t>(s, 4);
  detail::storeLE<std::uint16_t>(s, kExtraBytesSize);
  putText(s, "extra bytes", 32);
  s.append(2, '\0');
  s += static_cast<char>(9);  // data type 9: float
  s += static_cast<char>(0);  // options: no no_data, min, max, scale or offset
  putText(s, name, 32);
  s.append(4 + 8 + 16 + 8 + 16 + 8 + 16 + 8 + 16 + 8 + 16, '\0');
  putText(s, "probability the point is wood", 32);
  return s;
}

void writeLas(std::ostream& out, const geom::PointCloud& cloud, const std::vector<std::uint8_t>& codes,
              const std::vector<float>& p, const std::string& name) {
  const geom::BBox box = cloud.bounds();
  const double span = (box.max - box.min).maxCoeff();
  double unit = 1e-4;
  while (span / unit > 2.0e9) unit *= 10;  // int32 coordinates
  const geom::Vec3 scale = geom::Vec3::Constant(unit);
  const geom::Vec3 offset = box.min.array().floor();
  std::string buf = lasHeader(cloud.size(), scale, offset, box) + extraBytesVlr(name);
  const bool hasIntensity = !cloud.intensity.empty();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3 q = ((cloud.positions[i] - offset).array() / scale.array()).round();
    for (int k = 0; k < 3; ++k) detail::storeLE(buf, static_cast<std::int32_t>(q[k]));
    const float in = hasIntensity ? std::clamp(cloud.intensity[i], 0.0f, 65535.0f) : 0.0f;
    detail::storeLE(buf, static_cast<std::uint16_t>(std::lround(in)));
    buf += static_cast<char>(0x11);  // return 1 of 1
    buf += static_cast<char>(0);     // flags, channel, direction, edge
    buf += static_cast<char>(codes[i]);
    buf += static_cast<char>(0);             // user data
    detail::storeLE<std::int16_t>(buf, 0);   // scan angle
    detail::storeLE<std::uint16_t>(buf, 0);  // point source id
    detail::storeLE<double>(buf, 0.0);       // GPS time
    detail::storeLE(buf, p[i]);
    detail::flushIfFull(out, buf);
  }
  detail::writeAll(out, buf);
}

}  // namespace

void writeClassifiedCloud(std::ostream& out, bool las, const geom::PointCloud& cloud,
                          const std::vector<std::uint8_t>& codes, const std::vector<float>& probability,
                          const std::string& probabilityName) {
  checkArrays(cloud, codes, probability);
  if (las)
    writeLas(out, cloud, codes, probability, probabilityName);
  else
    writePly(out, cloud, codes, probability, probabilityName);
}

void writeClassifiedCloud(const std::filesystem::path& path, const geom::PointCloud& cloud,
                          const std::vector<std::uint8_t>& codes, const std::vector<float>& probability,
                          const std::string& probabilityName) {
  const std::string ext = lowercase(path.extension().string());
  if (ext != ".ply" && ext != ".las")
    throw OutputError(path.string() + ": a classified cloud is written as .ply or .las, not '" + ext + "'");
  checkArrays(cloud, codes, probability);
  writeFileAtomically(path, [&](std::ostream& out) {
    writeClassifiedCloud(out, ext == ".las", cloud, codes, probability, probabilityName);
  });
}

}  // namespace treesketch::io
