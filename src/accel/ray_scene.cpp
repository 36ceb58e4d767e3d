// Ray casting with Embree 3: see include/treesketch/accel/ray_scene.h.
// Embree usage follows its tutorials (error callback first, then device -> scene -> geometry ->
// commit; rtcIntersect1 per ray for incoherent rays).
#include "treesketch/accel/ray_scene.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::accel {

namespace {

using geom::Vec3;

// The message of the last Embree error on this thread (set by the device's error callback).
thread_local std::string tLastEmbreeError;

void embreeErrorCallback(void* /*userPtr*/, RTCError code, const char* str) {
  tLastEmbreeError = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (str ? str : "(no message)");
}

// Throws std::runtime_error when the device reports an error since the last check.
void throwOnEmbreeError(RTCDevice device, const char* what) {
  RTCError err = rtcGetDeviceError(device);
  if (err == RTC_ERROR_NONE) return;
  std::string msg =
      tLastEmbreeError.empty() ? "Embree error " + std::to_string(static_cast<int>(err)) : tLastEmbreeError;
  tLastEmbreeError.clear();
  if (err == RTC_ERROR_OUT_OF_MEMORY) throw std::bad_alloc();
  throw std::runtime_error(std::string(what) + ": " + msg);
}

RTCBuildQuality toEmbree(BuildQuality q) {
  switch (q) {
    case BuildQuality::Low:
      return RTC_BUILD_QUALITY_LOW;
    case BuildQuality::Medium:
      return RTC_BUILD_QUALITY_MEDIUM;
    case BuildQuality::High:
      return RTC_BUILD_QUALITY_HIGH;
  }
  return RTC_BUILD_QUALITY_MEDIUM;
}

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Vec3 centre = Vec3::Zero();  // world -> Embree frame: subtract centre
  geom::BBox bounds;
  // Per mesh, per triangle: unit normal and offset (n . x = offset on the plane), world
  // coordinates, double precision; one cache line per hit to refine t (a zero normal marks a
  // degenerate triangle).
  struct Plane {
    Vec3 normal;
    double offset;
  };
  std::vector<std::vector<Plane>> planes;
  std::size_t meshCount = 0;
  std::size_t triangleCount = 0;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // One Embree ray query in the Embree frame; fills `hit` (world coordinates).
  RayHit trace(const Vec3& origin, const Vec3& dir, double tnear, double tfar) const {
    RayHit hit;
    if (!finite(origin) || !finite(dir) || !std::isfinite(tnear) || std::isnan(tfar) || dir.squaredNorm() == 0.0 ||
        tfar < tnear)
      return hit;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);  // flags = incoherent
    RTCRayHit rh;
    const Vec3 o = origin - centre;
    rh.ray.org_x = static_cast<float>(o.x());
    rh.ray.org_y = static_cast<float>(o.y());
    rh.ray.org_z = static_cast<float>(o.z());
    rh.ray.dir_x = static_cast<float>(dir.x());
    rh.ray.dir_y = static_cast<float>(dir.y());
    rh.ray.dir_z = static_cast<float>(dir.z());
    rh.ray.tnear = static_cast<float>(std::max(0.0, tnear));
    rh.ray.tfar = static_cast<float>(tfar);  // +inf stays +inf
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;

    hit.meshIndex = static_cast<std::int32_t>(rh.hit.geomID);
    hit.primId = rh.hit.primID;
    double t = rh.ray.tfar;
    // Refine t in double: intersect the ray with the hit triangle's plane (world coordinates).
    const Plane& pl = planes[rh.hit.geomID][rh.hit.primID];
    const double denom = pl.normal.dot(dir);
    // Trust the plane only when the ray is not nearly parallel to it (cos > 1e-3).
    if (std::abs(denom) > 1e-3 * dir.norm()) t = (pl.offset - pl.normal.dot(origin)) / denom;
    hit.t = t;
    hit.point = origin + t * dir;
    return hit;
  }
};

RayScene::RayScene(const geom::TriMesh& mesh, const RaySceneOptions& options)
    : RayScene(std::vector<geom::TriMesh>{mesh}, options) {}

RayScene::RayScene(const std::vector<geom::TriMesh>& meshes, const RaySceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  // Validate; keep each triangle's plane in double precision.
  s.meshCount = meshes.size();
  s.planes.resize(meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const geom::TriMesh& in = meshes[i];
    for (std::size_t t = 0; t < in.triangles.size(); ++t)
      for (std::uint32_t v : in.triangles[t])
        if (v >= in.vertices.size())
          throw OptionsError("ray scene: mesh " + std::to_string(i) + " triangle " + std::to_string(t) +
                             " has vertex index " + std::to_string(v) + " but the mesh has " +
                             std::to_string(in.vertices.size()) + " vertices");
    for (std::size_t v = 0; v < in.vertices.size(); ++v)
      if (!finite(in.vertices[v]))
        throw OptionsError("ray scene: mesh " + std::to_string(i) + " vertex " + std::to_string(v) +
                           " is not finite (NaN or Inf)");
    std::vector<Impl::Plane>& planes = s.planes[i];
    planes.resize(in.triangles.size());
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
      const Vec3& a = in.vertices[in.triangles[t][0]];
      Vec3 n = (in.vertices[in.triangles[t][1]] - a).cross(in.vertices[in.triangles[t][2]] - a);
      const double len = n.norm();
      n = len > 0.0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
      planes[t] = {n, n.dot(a)};
    }
    s.triangleCount += in.triangles.size();
    if (!in.triangles.empty()) s.bounds.add(in.bounds());
  }
  s.centre = s.bounds.empty() ? Vec3::Zero() : s.bounds.centre();

  s.device = rtcNewDevice(nullptr);
  if (!s.device)
    throw std::runtime_error("ray scene: cannot create an Embree device (error " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(s.device, embreeErrorCallback, nullptr);
  s.scene = rtcNewScene(s.device);
  throwOnEmbreeError(s.device, "ray scene: new scene");
  rtcSetSceneBuildQuality(s.scene, toEmbree(options.quality));

  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const geom::TriMesh& m = meshes[i];
    if (m.triangles.empty()) continue;
    RTCGeometry g = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    throwOnEmbreeError(s.device, "ray scene: new geometry");
    rtcSetGeometryBuildQuality(g, toEmbree(options.quality));
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), m.triangles.size()));
    if (!vb || !ib) {
      rtcReleaseGeometry(g);
      throwOnEmbreeError(s.device, "ray scene: geometry buffers");
      throw std::runtime_error("ray scene: Embree returned no geometry buffer");
    }
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      const Vec3 p = m.vertices[v] - s.centre;
      vb[3 * v + 0] = static_cast<float>(p.x());
      vb[3 * v + 1] = static_cast<float>(p.y());
      vb[3 * v + 2] = static_cast<float>(p.z());
    }
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) ib[3 * t + k] = m.triangles[t][k];
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(s.scene, g, static_cast<unsigned>(i));  // geomID == input mesh index
    rtcReleaseGeometry(g);
    throwOnEmbreeError(s.device, "ray scene: attach geometry");
  }
  rtcCommitScene(s.scene);
  throwOnEmbreeError(s.device, "ray scene: commit (BVH build)");
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

RayHit RayScene::intersect(const geom::Vec3& origin, const geom::Vec3& dir, double tnear, double tfar) const {
  return impl_->trace(origin, dir, tnear, tfar);
}

std::vector<RayHit> RayScene::intersectAll(const std::vector<Ray>& rays, const ProgressFn& progress) const {
  std::vector<RayHit> hits(rays.size());
  const std::uint64_t total = rays.size();
  std::atomic<std::uint64_t> done{0};
  const Impl& s = *impl_;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        hits[i] = s.trace(rays[i].origin, rays[i].dir, rays[i].tnear, rays[i].tfar);
                      if (progress) progress(done.fetch_add(r.size()) + r.size(), total);
                    });
  return hits;
}

std::size_t RayScene::meshCount() const { return impl_->meshCount; }
std::size_t RayScene::triangleCount() const { return impl_->triangleCount; }
const geom::BBox& RayScene::bounds() const { return impl_->bounds; }

}  // namespace treesketch::accel
