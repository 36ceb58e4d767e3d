// Hausdorff comparison as Metro (Cignoni, Rocchini & Scopigno 1998) and MeshLab's filter (thesis
// §2.5, §4.5): sample, measure each sample's closest-point distance, summarise.
#include "treesketch/compare/hausdorff.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::compare {

using geom::Vec3;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void checkInput(const geom::TriMesh& mesh, const char* role) {
  if (mesh.triangles.empty()) throw OptionsError(std::string("comparison: the ") + role + " mesh has no triangles");
  const std::size_t nv = mesh.vertices.size();
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (auto v : mesh.triangles[i])
      if (v >= nv)
        throw OptionsError(std::string("comparison: the ") + role + " mesh's triangle " + std::to_string(i) +
                           " references vertex " + std::to_string(v) + " of " + std::to_string(nv));
  for (std::size_t i = 0; i < nv; ++i)
    if (!mesh.vertices[i].allFinite())
      throw OptionsError(std::string("comparison: the ") + role + " mesh's vertex " + std::to_string(i) +
                         " is NaN or infinite");
}

void checkInput(const geom::PointCloud& cloud, const char* role) {
  if (cloud.empty()) throw OptionsError(std::string("comparison: the ") + role + " point cloud is empty");
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (!cloud.positions[i].allFinite())
      throw OptionsError(std::string("comparison: the ") + role + " point cloud's point " + std::to_string(i) +
                         " is NaN or infinite");
}

void checkOptions(const CompareOptions& o) {
  if (std::isnan(o.maxDistance) || o.maxDistance < 0)
    throw OptionsError("comparison: the search distance must be >= 0, got " + std::to_string(o.maxDistance));
  if (!std::isfinite(o.maxDistanceFraction) || o.maxDistanceFraction < 0)
    throw OptionsError("comparison: the search distance fraction must be >= 0, got " +
                       std::to_string(o.maxDistanceFraction));
  if (o.histogramBins < 1)
    throw OptionsError("comparison: histogram bins must be >= 1, got " + std::to_string(o.histogramBins));
  if (!o.sampling.vertices && !o.sampling.edges && !o.sampling.faces)
    throw OptionsError("comparison: no sample kind enabled (vertices, edges, faces)");
}

double searchDistance(const CompareOptions& o, double diagonal) {
  double d = o.maxDistance;
  if (o.maxDistanceFraction > 0) d = std::min(d, o.maxDistanceFraction * diagonal);
  return d;
}

template <class Index>
DistanceReport measure(const SurfaceSamples& samples, double diagonal, const Index& index, const CompareOptions& o) {
  const double maxDistance = searchDistance(o, diagonal);
  std::vector<accel::ClosestHit> hits = index.queryAll(samples.points, maxDistance, o.progress);
  std::vector<double> d(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) d[i] = hits[i].found() ? hits[i].distance : kInf;
  DistanceReport r = summarizeDistances(d, diagonal, o.histogramBins);
  r.maxDistance = maxDistance;
  r.vertexSamples = samples.vertexSamples;
  r.edgeSamples = samples.edgeSamples;
  r.faceSamples = samples.faceSamples;
  if (o.keepSamples) {
    r.distances = std::move(d);
    r.sampleKinds = samples.kinds;
    r.sampleVertex = samples.vertex;
  }
  return r;
}

SurfaceSamples samplesOf(const geom::TriMesh& mesh, const SamplingOptions& o) { return sampleSurface(mesh, o); }
SurfaceSamples samplesOf(const geom::PointCloud& cloud, const SamplingOptions& o) { return sampleCloud(cloud, o); }

/// Every comparison: check the inputs, index the target (`Index`: the closest-point query for the
/// target's kind), sample the other, measure.
template <class Index, class Sampled, class Target>
DistanceReport compareWith(const Sampled& sampled, const Target& target, const CompareOptions& options) {
  checkOptions(options);
  checkInput(sampled, "sampled");
  checkInput(target, "target");
  Index index(target, options.accel);
  return measure(samplesOf(sampled, options.sampling), sampled.bounds().diagonal(), index, options);
}

}  // namespace

DistanceReport compareMeshes(const geom::TriMesh& sampled, const geom::TriMesh& target, const CompareOptions& options) {
  return compareWith<accel::MeshClosestPoint>(sampled, target, options);
}

DistanceReport compareMeshToCloud(const geom::TriMesh& sampled, const geom::PointCloud& target,
                                  const CompareOptions& options) {
  return compareWith<accel::CloudClosestPoint>(sampled, target, options);
}

DistanceReport compareCloudToMesh(const geom::PointCloud& sampled, const geom::TriMesh& target,
                                  const CompareOptions& options) {
  return compareWith<accel::MeshClosestPoint>(sampled, target, options);
}

void finishBoth(BothReport& r) {
  if (r.forward.samplesUsed > 0 && r.backward.samplesUsed > 0) {
    r.hausdorff = std::max(r.forward.max, r.backward.max);
    r.hausdorffPercent = r.forward.percent(r.hausdorff);
  } else {
    r.hausdorff = r.hausdorffPercent = std::numeric_limits<double>::quiet_NaN();
  }
}

BothReport compareBoth(const geom::TriMesh& original, const geom::TriMesh& reconstruction,
                       const CompareOptions& options) {
  BothReport r;
  r.forward = compareMeshes(original, reconstruction, options);
  r.backward = compareMeshes(reconstruction, original, options);
  finishBoth(r);
  return r;
}

nlohmann::json toJson(const BothReport& r) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"forward", toJson(r.forward)},
          {"backward", toJson(r.backward)},
          {"hausdorff", number(r.hausdorff)},
          {"hausdorffPercent", number(r.hausdorffPercent)}};
}

namespace {

/// Both fillVertexDistances: check the target and the mesh's vertices, index the target
/// (`Index`: the closest-point query for its kind), measure the vertices still without a distance.
template <class Index, class Target>
void fillMissing(const geom::TriMesh& mesh, const Target& target, double maxDistance, std::vector<double>& distances) {
  checkInput(target, "target");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      throw OptionsError("comparison: vertex " + std::to_string(i) + " is NaN or infinite");
  const Index index(target);
  distances.resize(mesh.vertices.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::size_t> todo;
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < distances.size(); ++i)
    if (std::isnan(distances[i])) {
      todo.push_back(i);
      points.push_back(mesh.vertices[i]);
    }
  std::vector<accel::ClosestHit> hits = index.queryAll(points, maxDistance);
  for (std::size_t k = 0; k < todo.size(); ++k) distances[todo[k]] = hits[k].found() ? hits[k].distance : kInf;
}

}  // namespace

void fillVertexDistances(const geom::TriMesh& mesh, const geom::TriMesh& target, double maxDistance,
                         std::vector<double>& distances) {
  fillMissing<accel::MeshClosestPoint>(mesh, target, maxDistance, distances);
}

void fillVertexDistances(const geom::TriMesh& mesh, const geom::PointCloud& target, double maxDistance,
                         std::vector<double>& distances) {
  fillMissing<accel::CloudClosestPoint>(mesh, target, maxDistance, distances);
}

std::vector<double> vertexDistancesFromReport(const DistanceReport& report, std::size_t vertexCount) {
  std::vector<double> out(vertexCount, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < report.sampleVertex.size() && i < report.distances.size(); ++i) {
    const std::int64_t v = report.sampleVertex[i];
    if (v >= 0 && static_cast<std::size_t>(v) < vertexCount) out[v] = report.distances[i];
  }
  return out;
}

}  // namespace treesketch::compare
