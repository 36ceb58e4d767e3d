// Fuzz harness: closest points and `compare` on hostile geometry. The input is decoded into a
// small mesh (up to 16 vertices, 16 triangles; coordinates from tiny to near DBL_MAX, repeated and
// nearly repeated vertices, so degenerate triangles are common) and up to 16 query points.
// Contract checked: every call returns; nothing but OptionsError is thrown; no distance is NaN;
// where all coordinates are within ±1e150 (squared distances cannot overflow a double) every
// query finds the same distance as a brute-force search over all triangles (1e-9 relative),
// queryAll agrees with query, and compareMeshes gives ordered, finite statistics.
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "fuzz_support.h"
#include "treesketch/accel/closest_point.h"
#include "treesketch/compare/hausdorff.h"
#include "treesketch/util/error.h"

using namespace treesketch;

namespace {

// One thread: the batches here are tiny, and thread hand-offs would dominate every run (the
// answers do not depend on the thread count).
const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);

constexpr double kSaneRange = 1e150;  // beyond this, squared distances may overflow (not checked)

geom::Vec3 nextVec3(fuzz::ByteSource& in) {
  const double x = fuzz::nextDouble(in), y = fuzz::nextDouble(in);
  return {x, y, fuzz::nextDouble(in)};
}

// A vertex: a new point, or a previous vertex moved by a tiny or zero step (degenerate triangles).
geom::Vec3 nextVertex(fuzz::ByteSource& in, const std::vector<geom::Vec3>& previous) {
  const std::uint8_t mode = in.next<std::uint8_t>();
  if (previous.empty() || mode < 128) return nextVec3(in);
  const geom::Vec3& base = previous[mode % previous.size()];
  if (mode < 192) return base;
  const geom::Vec3 step = nextVec3(in) * std::ldexp(1.0, -static_cast<int>(in.next<std::uint8_t>() % 64));
  const geom::Vec3 moved = base + step;
  // Near DBL_MAX a step can overflow to infinity: the library refuses such a mesh (OptionsError,
  // tested in tests/accel), and the harness's meshes are finite by contract.
  return moved.allFinite() ? moved : base;
}

std::string describe(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
std::string describe(const geom::Vec3& v) {
  return "(" + describe(v.x()) + " " + describe(v.y()) + " " + describe(v.z()) + ")";
}
std::string describe(const geom::TriMesh& mesh) {
  std::string s;
  for (const auto& t : mesh.triangles)
    s += "[" + describe(mesh.vertices[t[0]]) + describe(mesh.vertices[t[1]]) + describe(mesh.vertices[t[2]]) + "]";
  return s;
}

bool sane(const std::vector<geom::Vec3>& points) {
  return std::all_of(points.begin(), points.end(),
                     [](const geom::Vec3& p) { return p.cwiseAbs().maxCoeff() <= kSaneRange; });
}

double bruteForce(const geom::TriMesh& mesh, const geom::Vec3& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const geom::Vec3 c =
        accel::closestPointOnTriangle(q, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    best = std::min(best, (c - q).norm());
  }
  return best;
}

void checkQueries(const geom::TriMesh& mesh, const std::vector<geom::Vec3>& queries, double maxDistance,
                  const accel::ClosestPointOptions& accelOptions, bool checked) {
  const accel::MeshClosestPoint index(mesh, accelOptions);
  std::vector<accel::ClosestHit> single;
  for (const geom::Vec3& q : queries) {
    const accel::ClosestHit hit = index.query(q, maxDistance);
    FUZZ_CHECK(!std::isnan(hit.distance), "closest point: NaN distance");
    single.push_back(hit);
    if (!checked) continue;
    const double expected = bruteForce(mesh, q);
    if (expected <= maxDistance) {
      FUZZ_CHECK(hit.found(), "closest point: nothing found within the search distance " + describe(maxDistance) +
                                  " (brute force: " + describe(expected) + ") at query " + describe(q) + ", mesh " +
                                  describe(mesh));
      FUZZ_CHECK(hit.point.allFinite(), "closest point: non-finite point");
      FUZZ_CHECK(hit.distance <= expected * (1 + 1e-9) && hit.distance >= expected * (1 - 1e-9),
                 "closest point: distance " + describe(hit.distance) + " differs from brute force " +
                     describe(expected) + " at query " + describe(q) + ", mesh " + describe(mesh));
    }
  }
  const std::vector<accel::ClosestHit> all = index.queryAll(queries, maxDistance);
  FUZZ_CHECK(all.size() == queries.size(), "queryAll: wrong number of answers");
  for (std::size_t i = 0; checked && i < all.size(); ++i)
    FUZZ_CHECK(all[i].found() == single[i].found() && (!all[i].found() || all[i].distance == single[i].distance),
               "queryAll and query disagree");
}

void checkCompare(const geom::TriMesh& original, const geom::TriMesh& other,
                  const accel::ClosestPointOptions& accelOptions, bool checked) {
  compare::CompareOptions options;
  options.sampling.count = 32;
  options.accel = accelOptions;
  compare::BothReport report;
  try {
    report = compare::compareBoth(original, other, options);
  } catch (const OptionsError&) {
    return;
  }
  for (const compare::DistanceReport* r : {&report.forward, &report.backward}) {
    FUZZ_CHECK(r->samplesUsed + r->samplesDropped == r->vertexSamples + r->edgeSamples + r->faceSamples,
               "compare: samples lost");
    if (!checked || r->samplesUsed == 0) continue;
    FUZZ_CHECK(std::isfinite(r->min) && std::isfinite(r->max) && std::isfinite(r->mean) && std::isfinite(r->rms),
               "compare: non-finite statistics");
    FUZZ_CHECK(0 <= r->min && r->min <= r->mean * (1 + 1e-12) && r->mean <= r->max * (1 + 1e-12),
               "compare: statistics out of order");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteSource in(data, size);
  geom::TriMesh mesh;
  const std::uint32_t vertexCount = 3 + in.next<std::uint8_t>() % 14;
  for (std::uint32_t i = 0; i < vertexCount; ++i) mesh.vertices.push_back(nextVertex(in, mesh.vertices));
  const int triangleCount = 1 + in.next<std::uint8_t>() % 16;
  for (int i = 0; i < triangleCount; ++i) {
    const std::uint8_t a = in.next<std::uint8_t>(), b = in.next<std::uint8_t>(), c = in.next<std::uint8_t>();
    mesh.triangles.push_back({a % vertexCount, b % vertexCount, c % vertexCount});
  }
  const int queryCount = 1 + in.next<std::uint8_t>() % 16;
  std::vector<geom::Vec3> queries;
  for (int i = 0; i < queryCount; ++i) queries.push_back(nextVertex(in, mesh.vertices));
  const std::uint8_t flags = in.next<std::uint8_t>();
  const double maxDistance = (flags & 1) ? std::abs(fuzz::nextDouble(in)) : std::numeric_limits<double>::infinity();

  // Morton ordering of a batch (sorting by 16-bit-per-axis codes) costs more than a batch of 16
  // here; one input in four uses it, so its handling of extreme boxes is fuzzed too.
  accel::ClosestPointOptions accelOptions;
  accelOptions.mortonOrder = (flags & 6) == 0;
  accelOptions.warmStart = (flags & 8) == 0;
  accelOptions.leafSize = 1 + (flags >> 4) % 8;

  const bool checked = sane(mesh.vertices) && sane(queries);
  checkQueries(mesh, queries, maxDistance, accelOptions, checked);
  // compare: the mesh against a second one made of the queries (three corners a triangle).
  geom::TriMesh other;
  other.vertices = queries;
  for (std::uint32_t i = 0; i + 2 < queries.size(); i += 3) other.triangles.push_back({i, i + 1, i + 2});
  checkCompare(mesh, other, accelOptions, checked);
  return 0;
}
