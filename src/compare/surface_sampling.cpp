// Metro/MeshLab-style surface sampling (vertices, evenly spaced edge points, area-weighted face
// points), after the descriptions in Cignoni et al. 1998 and MeshLab's Hausdorff filter docs.
#include "treesketch/compare/surface_sampling.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::compare {

using geom::Vec3;

const char* toString(SampleKind kind) {
  switch (kind) {
    case SampleKind::Vertex:
      return "vertex";
    case SampleKind::Edge:
      return "edge";
    case SampleKind::Face:
      return "face";
  }
  return "?";
}

namespace {

// Portable random numbers: std::mt19937_64 is fully specified, the standard distributions are
// not, so the conversions are done here.
struct Rng {
  std::mt19937_64 engine;
  Rng(std::uint64_t seed, std::uint64_t stream)
      : engine(seed * 0x9E3779B97F4A7C15ULL + stream * 0xD1B54A32D192ED03ULL) {}
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
  /// Uniform in [0, n), n > 0 (modulo bias below 2^-40 for n < 2^24: negligible here).
  std::uint64_t below(std::uint64_t n) { return engine() % n; }
};

constexpr std::uint64_t kVertexStream = 1, kFaceStream = 2;

// Seeded random subset of `count` of the indices `pool` (partial Fisher-Yates), in pool order
// for cache-friendly results; all of them when count >= pool size.
std::vector<std::int64_t> chooseSubset(std::vector<std::int64_t> pool, std::uint64_t count, std::uint64_t seed) {
  if (count >= pool.size()) return pool;
  Rng rng(seed, kVertexStream);
  for (std::uint64_t i = 0; i < count; ++i) std::swap(pool[i], pool[i + rng.below(pool.size() - i)]);
  pool.resize(count);
  std::sort(pool.begin(), pool.end());
  return pool;
}

void addSample(SurfaceSamples& s, const Vec3& p, SampleKind kind, std::int64_t vertex) {
  s.points.push_back(p);
  s.kinds.push_back(kind);
  s.vertex.push_back(vertex);
}

void sampleVertices(const geom::TriMesh& mesh, std::uint64_t count, std::uint64_t seed, SurfaceSamples& out) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.triangles)
    for (auto v : t) used[v] = 1;
  std::vector<std::int64_t> pool;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) pool.push_back(static_cast<std::int64_t>(i));
  for (std::int64_t v : chooseSubset(std::move(pool), count, seed))
    addSample(out, mesh.vertices[v], SampleKind::Vertex, v);
  out.vertexSamples = out.points.size();
}

void sampleEdges(const geom::TriMesh& mesh, std::uint64_t count, SurfaceSamples& out) {
  // Unique undirected edges, in a deterministic order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a == b) continue;
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double total = 0;
  for (const auto& [a, b] : edges) total += (mesh.vertices[b] - mesh.vertices[a]).norm();
  if (!(total > 0) || count == 0) return;
  // Walk the edges end to end; sample i sits at arc length (i + 1/2) * step.
  const double step = total / static_cast<double>(count);
  const std::size_t before = out.points.size();
  std::uint64_t i = 0;
  double start = 0;  // arc length where the current edge starts
  for (std::size_t e = 0; e < edges.size() && i < count; ++e) {
    const Vec3& a = mesh.vertices[edges[e].first];
    const Vec3& b = mesh.vertices[edges[e].second];
    const double len = (b - a).norm();
    const double end = start + len;
    const bool last = e + 1 == edges.size();
    while (i < count) {
      const double s = (static_cast<double>(i) + 0.5) * step;
      if (s >= end && !last) break;  // rounding may leave the final samples just past the end
      const double t = len > 0 ? std::clamp((s - start) / len, 0.0, 1.0) : 0.0;
      addSample(out, a + t * (b - a), SampleKind::Edge, -1);
      ++i;
    }
    start = end;
  }
  out.edgeSamples = out.points.size() - before;
}

void sampleFaces(const geom::TriMesh& mesh, std::uint64_t count, std::uint64_t seed, SurfaceSamples& out) {
  const std::size_t nt = mesh.triangles.size();
  std::vector<double> cdf(nt);
  double total = 0;
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[i];
    total += 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
    cdf[i] = total;
  }
  if (!(total > 0) || count == 0) return;
  Rng rng(seed, kFaceStream);
  const std::size_t before = out.points.size();
  for (std::uint64_t i = 0; i < count; ++i) {
    const double r = rng.uniform() * total;
    std::size_t f = std::upper_bound(cdf.begin(), cdf.end(), r) - cdf.begin();
    f = std::min(f, nt - 1);
    // Uniform on the triangle: fold the unit square's upper half onto the lower one.
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const auto& t = mesh.triangles[f];
    const Vec3& a = mesh.vertices[t[0]];
    addSample(out, a + u * (mesh.vertices[t[1]] - a) + v * (mesh.vertices[t[2]] - a), SampleKind::Face, -1);
  }
  out.faceSamples = out.points.size() - before;
}

}  // namespace

SurfaceSamples sampleSurface(const geom::TriMesh& mesh, const SamplingOptions& options) {
  const std::size_t nv = mesh.vertices.size();
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (auto v : mesh.triangles[i])
      if (v >= nv)
        throw OptionsError("sampling: triangle " + std::to_string(i) + " references vertex " + std::to_string(v) +
                           " of " + std::to_string(nv));
  const std::uint64_t count = options.count > 0 ? options.count : nv;
  SurfaceSamples out;
  if (mesh.triangles.empty()) return out;
  if (options.vertices) sampleVertices(mesh, count, options.seed, out);
  if (options.edges) sampleEdges(mesh, count, out);
  if (options.faces) sampleFaces(mesh, count, options.seed, out);
  return out;
}

SurfaceSamples sampleCloud(const geom::PointCloud& cloud, const SamplingOptions& options) {
  const std::uint64_t count = options.count > 0 ? options.count : cloud.size();
  std::vector<std::int64_t> pool(cloud.size());
  std::iota(pool.begin(), pool.end(), std::int64_t{0});
  SurfaceSamples out;
  for (std::int64_t i : chooseSubset(std::move(pool), count, options.seed))
    addSample(out, cloud.positions[i], SampleKind::Vertex, i);
  out.vertexSamples = out.points.size();
  return out;
}

}  // namespace treesketch::compare
