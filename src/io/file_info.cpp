#include "treesketch/io/file_info.h"

#include "io/io_util.h"
#include "treesketch/io/las.h"
#include "treesketch/io/obj.h"
#include "treesketch/io/ply.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/xyz.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

std::string num(double v) {
  std::string s;
  detail::appendNumber(s, v);
  return s;
}

std::string vec(const geom::Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

std::string describe(const PlyElement& e) {
  std::string s = std::to_string(e.count) + " x (";
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    const PlyProperty& p = e.properties[i];
    if (i) s += ", ";
    if (p.isList)
      s += std::string("list ") + toString(p.countType) + " " + toString(p.type) + " " + p.name;
    else
      s += std::string(toString(p.type)) + " " + p.name;
  }
  return s + ")";
}

}  // namespace

FileInfo inspectFile(const std::filesystem::path& path) {
  FileInfo info;
  CloudReadOptions anyCount;
  anyCount.minPoints = 1;
  std::string ext = detail::lowerExtension(path);
  if (ext == ".ply") {
    PlyHeader h = readPlyHeader(path);
    info.format = std::string("PLY ") + toString(h.format);
    for (const auto& c : h.comments) info.details.emplace_back("comment", c);
    for (const auto& e : h.elements) info.details.emplace_back("element " + e.name, describe(e));
    if (h.find("face")) {
      info.isMesh = true;
      info.mesh = readPlyMesh(path);
    } else {
      info.cloud = readPlyPointCloud(path, anyCount);
    }
  } else if (ext == ".obj") {
    ObjStats st;
    info.format = "OBJ";
    info.isMesh = true;
    info.mesh = readObj(path, &st);
    info.details.emplace_back("faces", std::to_string(st.polygons) + " (" + std::to_string(st.nonTriangles) +
                                           " with more than 3 corners, fan-triangulated)");
    info.details.emplace_back("ignored lines", std::to_string(st.ignoredLines) + " (vt, vn, g, usemtl, ...)");
  } else if (cloudFormatFromPath(path) == CloudFormat::Las) {
    LasHeader h;
    info.cloud = readLas(path, anyCount, &h);
    info.format = std::string(h.compressed ? "LAZ (compressed LAS) " : "LAS ") + std::to_string(h.versionMajor) + "." +
                  std::to_string(h.versionMinor);
    info.details.emplace_back("system identifier", h.systemId);
    info.details.emplace_back("generating software", h.generatingSoftware);
    info.details.emplace_back("point data format", std::to_string(h.pointFormat));
    info.details.emplace_back("point record length", std::to_string(h.recordLength) + " bytes");
    if (h.compressed) {
      const LazInfo& z = h.laz;
      info.details.emplace_back(
          "compressor", "LASzip " + z.compressorName() + " (written by LASzip " + std::to_string(z.versionMajor) + "." +
                            std::to_string(z.versionMinor) + "r" + std::to_string(z.revision) + ")");
      info.details.emplace_back("compressed items", z.itemList());
      info.details.emplace_back("chunk size", z.chunkSize == kLazVariableChunkSize
                                                  ? std::string("variable")
                                                  : std::to_string(z.chunkSize) + " points");
      info.details.emplace_back("chunks", std::to_string(z.chunkCount));
    }
    info.details.emplace_back("header size", std::to_string(h.headerSize) + " bytes");
    info.details.emplace_back("offset to point data", std::to_string(h.offsetToPointData) + " bytes");
    info.details.emplace_back("variable length records", std::to_string(h.numVlrs));
    info.details.emplace_back("header point count", std::to_string(h.pointCount));
    info.details.emplace_back("withheld points",
                              std::to_string(h.withheld) + (h.withheld > 0 ? " (dropped on read)" : ""));
    info.details.emplace_back("scale", vec(h.scale));
    info.details.emplace_back("offset", vec(h.offset));
    info.details.emplace_back("header min", vec(h.min));
    info.details.emplace_back("header max", vec(h.max));
  } else {
    info.format = "XYZ text";
    info.cloud = readXyz(path, anyCount);
  }
  return info;
}

}  // namespace treesketch::io
