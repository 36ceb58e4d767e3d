#include "treesketch/io/point_cloud_io.h"

#include <sstream>

#include "io/io_util.h"
#include "treesketch/io/las.h"
#include "treesketch/io/obj.h"
#include "treesketch/io/ply.h"
#include "treesketch/io/xyz.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

CloudFormat cloudFormatFromPath(const std::filesystem::path& path) {
  std::string ext = detail::lowerExtension(path);
  if (ext == ".ply") return CloudFormat::Ply;
  if (ext == ".xyz" || ext == ".txt" || ext == ".csv" || ext == ".pts" || ext == ".asc") return CloudFormat::Xyz;
  if (ext == ".las" || ext == ".laz") return CloudFormat::Las;
  if (ext == ".obj") return CloudFormat::Obj;
  throw InputError(path.string() + ": unknown point cloud extension '" + ext +
                   "', expected .ply, .xyz, .txt, .csv, .pts, .asc, .las, .laz or .obj (its vertices)");
}

geom::PointCloud readPointCloud(std::istream& in, const std::string& source, CloudFormat format,
                                const CloudReadOptions& options) {
  switch (format) {
    case CloudFormat::Ply:
      return readPlyPointCloud(in, source, options);
    case CloudFormat::Xyz:
      return readXyz(in, source, options);
    case CloudFormat::Las:
      return readLas(in, source, options);
    case CloudFormat::Obj: {
      geom::PointCloud c = readObjVertices(in, source);
      checkCloudSize(c, source, options.minPoints);
      return c;
    }
  }
  throw InputError(source + ": unknown point cloud format");
}

geom::PointCloud readPointCloud(const std::filesystem::path& path, const CloudReadOptions& options) {
  CloudFormat f = cloudFormatFromPath(path);
  switch (f) {
    case CloudFormat::Ply:
      return readPlyPointCloud(path, options);
    case CloudFormat::Xyz:
      return readXyz(path, options);
    case CloudFormat::Las:
      return readLas(path, options);
    case CloudFormat::Obj:
      break;
  }
  std::string data = detail::readFile(path);
  std::istringstream in(std::move(data));
  return readPointCloud(in, path.string(), f, options);
}

void writePointCloud(std::ostream& out, CloudFormat format, const geom::PointCloud& cloud) {
  if (format == CloudFormat::Ply) return writePlyPointCloud(out, cloud);
  if (format == CloudFormat::Xyz) return writeXyz(out, cloud);
  throw OutputError("point clouds can be written as PLY or XYZ only");
}

void writePointCloud(const std::filesystem::path& path, const geom::PointCloud& cloud) {
  std::string ext = detail::lowerExtension(path);
  if (ext == ".ply") return writePlyPointCloud(path, cloud);
  if (ext == ".xyz" || ext == ".txt") return writeXyz(path, cloud);
  throw OutputError(path.string() + ": cannot write a point cloud as '" + ext + "', expected .ply or .xyz (or .txt)");
}

}  // namespace treesketch::io
