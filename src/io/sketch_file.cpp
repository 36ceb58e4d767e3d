// Sketch files and camera files (JSON, nlohmann). See include/treesketch/io/sketch_file.h.
#include "treesketch/io/sketch_file.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

using nlohmann::json;
using ojson = nlohmann::ordered_json;  // writing: keys in a readable order

namespace {

constexpr const char* kFormatName = "treesketch-sketch";
constexpr int kFormatVersion = 1;
/// A sketch with a wood lasso is written as version 2, so that a reader of version 1 (which would
/// take the lasso for a not-wood one) refuses it; every other sketch stays version 1.
constexpr int kWoodLassoVersion = 2;

/// Error context: "source: where: what".
struct Ctx {
  const std::string& source;
  std::string where;  // "node 7", "camera 2", "defaults", "" (top level)
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(source + ": " + (where.empty() ? "" : where + ": ") + what);
  }
};

std::string typeName(const json& j) { return j.type_name(); }

const json& field(const json& obj, const char* key, const Ctx& ctx) {
  auto it = obj.find(key);
  if (it == obj.end()) ctx.fail(std::string("missing \"") + key + "\"");
  return *it;
}

double number(const json& j, const std::string& what, const Ctx& ctx) {
  if (!j.is_number()) ctx.fail(what + ": expected a number, got " + typeName(j));
  double v = j.get<double>();
  if (!std::isfinite(v)) ctx.fail(what + ": not a finite number");
  return v;
}

long long integer(const json& j, const std::string& what, const Ctx& ctx) {
  if (!j.is_number_integer()) ctx.fail(what + ": expected an integer, got " + typeName(j));
  if (j.is_number_unsigned()) {
    auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max())) ctx.fail(what + ": out of range");
    return static_cast<long long>(u);
  }
  long long v = j.get<long long>();
  if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
    ctx.fail(what + ": out of range");
  return v;
}

std::vector<double> numbers(const json& obj, const char* key, std::size_t count, const Ctx& ctx) {
  const json& a = field(obj, key, ctx);
  std::string what = std::string("\"") + key + "\"";
  if (!a.is_array() || a.size() != count)
    ctx.fail(what + ": expected an array of " + std::to_string(count) + " numbers");
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = number(a[i], what + "[" + std::to_string(i) + "]", ctx);
  return out;
}

ojson mat4ToJson(const geom::Mat4& m) {
  ojson a = ojson::array();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a.push_back(m(r, c));
  return a;
}

geom::Mat4 mat4FromJson(const json& obj, const char* key, const Ctx& ctx) {
  std::vector<double> v = numbers(obj, key, 16, ctx);
  geom::Mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = v[4 * r + c];
  return m;
}

ojson cameraToJson(const geom::Camera& cam) {
  ojson j;
  j["view"] = mat4ToJson(cam.view);
  j["projection"] = mat4ToJson(cam.projection);
  j["viewport"] = {cam.viewport.x, cam.viewport.y, cam.viewport.width, cam.viewport.height};
  return j;
}

geom::Camera cameraFromJson(const json& j, const Ctx& ctx) {
  if (!j.is_object()) ctx.fail("expected a camera object, got " + typeName(j));
  geom::Camera cam;
  cam.view = mat4FromJson(j, "view", ctx);
  cam.projection = mat4FromJson(j, "projection", ctx);
  std::vector<double> vp = numbers(j, "viewport", 4, ctx);
  cam.viewport = geom::Viewport{vp[0], vp[1], vp[2], vp[3]};
  try {
    cam.validate("degenerate camera");
  } catch (const OptionsError& e) {
    ctx.fail(e.what());
  }
  return cam;
}

/// `base` is what a reader fills an absent field with (the file's defaults for a node, the
/// SamplingParams defaults for the defaults): maxGrowthSteps is written whenever it differs from
/// it, so a node's -1 (unlimited) under defaults with a cap reads back as -1.
ojson paramsToJson(const sketch::SamplingParams& p, const sketch::SamplingParams& base) {
  ojson j;
  j["sliceHalfThickness"] = p.sliceHalfThickness;
  j["lineEpsilon"] = p.lineEpsilon;
  j["lineEpsilonStep"] = p.lineEpsilonStep;
  j["enabled"] = p.enabled;
  if (p.maxGrowthSteps != base.maxGrowthSteps) j["maxGrowthSteps"] = p.maxGrowthSteps;
  return j;
}

sketch::SamplingParams paramsFromJson(const json& j, const sketch::SamplingParams& base, const Ctx& ctx) {
  if (!j.is_object()) ctx.fail("\"params\": expected an object, got " + typeName(j));
  sketch::SamplingParams p = base;
  auto num = [&](const char* key, double& out) {
    auto it = j.find(key);
    if (it != j.end()) out = number(*it, std::string("\"") + key + "\"", ctx);
  };
  num("sliceHalfThickness", p.sliceHalfThickness);
  num("lineEpsilon", p.lineEpsilon);
  num("lineEpsilonStep", p.lineEpsilonStep);
  auto it = j.find("enabled");
  if (it != j.end()) {
    if (!it->is_boolean()) ctx.fail("\"enabled\": expected true or false, got " + typeName(*it));
    p.enabled = it->get<bool>();
  }
  it = j.find("maxGrowthSteps");
  if (it != j.end()) {
    // Any int >= -1, as Sketch::validate accepts (what a sketch holds, its file can say).
    if (!it->is_number_integer() || it->get<std::int64_t>() < -1 ||
        it->get<std::int64_t>() > std::numeric_limits<int>::max())
      ctx.fail("\"maxGrowthSteps\": expected an integer >= -1 (-1: unlimited), got " + it->dump());
    p.maxGrowthSteps = static_cast<int>(it->get<std::int64_t>());
  }
  if (!(p.sliceHalfThickness > 0)) ctx.fail("sliceHalfThickness must be > 0");
  if (!(p.lineEpsilon > 0)) ctx.fail("lineEpsilon must be > 0");
  if (!(p.lineEpsilonStep > 0)) ctx.fail("lineEpsilonStep must be > 0");
  return p;
}

json parseJson(std::istream& in, const std::string& source) {
  if (!in) throw InputError(source + ": cannot read");
  try {
    return json::parse(in);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line L, column C: ..."
    auto pos = what.find("parse error");
    throw InputError(atOffset(source, e.byte, "malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos))));
  } catch (const json::exception& e) {
    // e.g. out_of_range.406 "number overflow parsing '1e999'": nlohmann gives no position.
    throw InputError(source + ": malformed JSON: " + e.what());
  }
}

sketch::Node nodeFromJson(const json& j, std::size_t index, const sketch::SamplingParams& defaults,
                          const std::string& source) {
  Ctx ctx{source, "node #" + std::to_string(index)};
  if (!j.is_object()) ctx.fail("expected a node object, got " + typeName(j));
  sketch::Node n;
  n.id = static_cast<sketch::NodeId>(integer(field(j, "id", ctx), "\"id\"", ctx));
  ctx.where = "node " + std::to_string(n.id);
  n.parent = static_cast<sketch::NodeId>(integer(field(j, "parent", ctx), "\"parent\"", ctx));
  if (n.parent < sketch::kNoNode) ctx.fail("\"parent\" must be -1 (root) or a node id");
  bool hasScreen = j.contains("screen") || j.contains("camera");
  bool hasPoint = j.contains("point") || j.contains("normal");
  if (hasScreen && hasPoint) ctx.fail("has both \"screen\"/\"camera\" and \"point\"/\"normal\"");
  if (!hasScreen && !hasPoint) ctx.fail("needs \"camera\" and \"screen\" (screen node) or \"point\" and \"normal\"");
  if (hasScreen) {
    long long cam = integer(field(j, "camera", ctx), "\"camera\"", ctx);
    if (cam < 0) ctx.fail("\"camera\" must be >= 0");
    n.camera = static_cast<int>(cam);
    std::vector<double> s = numbers(j, "screen", 2, ctx);
    n.screen = geom::Vec2(s[0], s[1]);
  } else {
    n.camera = -1;
    std::vector<double> p = numbers(j, "point", 3, ctx);
    std::vector<double> q = numbers(j, "normal", 3, ctx);
    n.point = geom::Vec3(p[0], p[1], p[2]);
    n.normal = geom::Vec3(q[0], q[1], q[2]);
    if (!(n.normal.norm() > 0)) ctx.fail("\"normal\" is zero");
  }
  auto it = j.find("params");
  n.params = it == j.end() ? defaults : paramsFromJson(*it, defaults, ctx);
  if (auto c = j.find("circle"); c != j.end()) {
    if (hasScreen) ctx.fail("\"circle\": a kept circle needs a point node (this is a screen node)");
    if (!c->is_object())
      ctx.fail("\"circle\": expected an object {\"centre\": [x, y, z], \"radius\": r}, got " + typeName(*c));
    Ctx cctx{source, ctx.where + ": \"circle\""};
    std::vector<double> centre = numbers(*c, "centre", 3, cctx);
    const double radius = number(field(*c, "radius", cctx), "\"radius\"", cctx);
    if (!(radius > 0)) cctx.fail("\"radius\" must be > 0");
    n.kept = sketch::KeptCircle{geom::Vec3(centre[0], centre[1], centre[2]), radius};
  }
  return n;
}

std::optional<SketchCloudRecord> cloudRecordFromJson(const json& root, const std::string& source) {
  auto it = root.find("cloud");
  if (it == root.end()) return std::nullopt;
  const Ctx ctx{source, "\"cloud\""};
  if (!it->is_object()) ctx.fail("expected an object {\"path\", \"points\", \"hash\"}, got " + typeName(*it));
  SketchCloudRecord r;
  const json& path = field(*it, "path", ctx);
  const json& points = field(*it, "points", ctx);
  const json& hash = field(*it, "hash", ctx);
  if (!path.is_string()) ctx.fail("\"path\": expected a string, got " + typeName(path));
  if (!points.is_number_unsigned()) ctx.fail("\"points\": expected a count, got " + points.dump());
  if (!hash.is_string()) ctx.fail("\"hash\": expected a string, got " + typeName(hash));
  r.path = path.get<std::string>();
  r.points = points.get<std::uint64_t>();
  r.hash = hash.get<std::string>();
  return r;
}

sketch::Sketch sketchFromJson(const json& root, const std::string& source) {
  Ctx top{source, ""};
  if (!root.is_object()) top.fail("expected a JSON object at the top level, got " + typeName(root));
  const json& format = field(root, "format", top);
  if (!format.is_string() || format.get<std::string>() != kFormatName)
    top.fail(std::string("\"format\" must be \"") + kFormatName + "\", got " + format.dump());
  long long version = integer(field(root, "version", top), "\"version\"", top);
  if (version != kFormatVersion && version != kWoodLassoVersion)
    top.fail("unsupported version " + std::to_string(version) + " (this program reads versions " +
             std::to_string(kFormatVersion) + " and " + std::to_string(kWoodLassoVersion) + ")");
  sketch::Sketch sk;
  if (auto it = root.find("up"); it != root.end()) {
    if (!it->is_string()) top.fail("\"up\": expected \"y\" or \"z\", got " + typeName(*it));
    try {
      sk.up = geom::parseUpAxis(it->get<std::string>());
    } catch (const OptionsError& e) {
      top.fail(e.what());
    }
  }
  if (auto it = root.find("defaults"); it != root.end()) sk.defaults = paramsFromJson(*it, {}, Ctx{source, "defaults"});
  const json& cams = field(root, "cameras", top);
  if (!cams.is_array()) top.fail("\"cameras\": expected an array, got " + typeName(cams));
  for (std::size_t i = 0; i < cams.size(); ++i)
    sk.insertRawCamera(cameraFromJson(cams[i], Ctx{source, "camera " + std::to_string(i)}));
  if (auto it = root.find("notWood"); it != root.end()) {
    // Added within version 1 (with the not-wood lasso): older files have none; older readers ignore it.
    if (!it->is_array()) top.fail("\"notWood\": expected an array, got " + typeName(*it));
    for (std::size_t i = 0; i < it->size(); ++i) {
      Ctx lctx{source, "not-wood lasso " + std::to_string(i)};
      const json& l = (*it)[i];
      if (!l.is_object()) lctx.fail("expected an object, got " + typeName(l));
      long long cam = integer(field(l, "camera", lctx), "\"camera\"", lctx);
      if (cam < 0 || cam >= static_cast<long long>(sk.cameras().size()))
        lctx.fail("camera " + std::to_string(cam) + " does not exist (the file has " +
                  std::to_string(sk.cameras().size()) + " cameras)");
      const json& poly = field(l, "polygon", lctx);
      if (!poly.is_array() || poly.size() < 3) lctx.fail("\"polygon\": expected an array of at least 3 [x, y]");
      std::vector<geom::Vec2> vs;
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const json& v = poly[k];
        const std::string what = "\"polygon\" vertex " + std::to_string(k);
        if (!v.is_array() || v.size() != 2) lctx.fail(what + ": expected [x, y]");
        vs.emplace_back(number(v[0], what + " x", lctx), number(v[1], what + " y", lctx));
      }
      bool wood = false;
      if (auto w = l.find("wood"); w != l.end()) {
        if (!w->is_boolean()) lctx.fail("\"wood\": expected true or false, got " + typeName(*w));
        wood = w->get<bool>();
      }
      try {
        if (wood)
          sk.addWoodLasso(static_cast<int>(cam), vs);
        else
          sk.addNotWoodLasso(static_cast<int>(cam), vs);
      } catch (const OptionsError& e) {
        lctx.fail(e.what());
      }
    }
  }
  const json& nodes = field(root, "nodes", top);
  if (!nodes.is_array()) top.fail("\"nodes\": expected an array, got " + typeName(nodes));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    sketch::Node n = nodeFromJson(nodes[i], i, sk.defaults, source);
    if (n.camera >= static_cast<int>(sk.cameras().size()))
      throw InputError(source + ": node " + std::to_string(n.id) + ": camera " + std::to_string(n.camera) +
                       " does not exist (the file has " + std::to_string(sk.cameras().size()) + " cameras)");
    try {
      sk.insertRaw(n);
    } catch (const OptionsError& e) {
      throw InputError(source + ": " + e.what());
    }
  }
  try {
    sk.validate();
  } catch (const OptionsError& e) {
    throw InputError(source + ": " + e.what());
  }
  return sk;
}

ojson sketchToJson(const sketch::Sketch& sk, const SketchCloudRecord* cloud = nullptr) {
  ojson j;
  j["format"] = kFormatName;
  j["version"] = sk.woodLassoCount() > 0 ? kWoodLassoVersion : kFormatVersion;
  if (cloud) j["cloud"] = ojson{{"path", cloud->path}, {"points", cloud->points}, {"hash", cloud->hash}};
  j["up"] = geom::toString(sk.up);
  j["defaults"] = paramsToJson(sk.defaults, sketch::SamplingParams{});  // absent = -1 = unlimited (thesis)
  j["cameras"] = ojson::array();
  for (const auto& c : sk.cameras()) j["cameras"].push_back(cameraToJson(c));
  if (!sk.notWood().empty()) {
    j["notWood"] = ojson::array();
    for (const auto& l : sk.notWood()) {
      ojson o;
      o["camera"] = l.camera;
      if (l.wood) o["wood"] = true;
      o["polygon"] = ojson::array();
      for (const auto& v : l.polygon) o["polygon"].push_back({v.x(), v.y()});
      j["notWood"].push_back(std::move(o));
    }
  }
  j["nodes"] = ojson::array();
  for (sketch::NodeId id : sk.topologicalOrder()) {
    const sketch::Node& n = sk.node(id);
    ojson o;
    o["id"] = n.id;
    o["parent"] = n.parent;
    if (n.isScreenNode()) {
      o["camera"] = n.camera;
      o["screen"] = {n.screen.x(), n.screen.y()};
    } else {
      o["point"] = {n.point.x(), n.point.y(), n.point.z()};
      o["normal"] = {n.normal.x(), n.normal.y(), n.normal.z()};
    }
    o["params"] = paramsToJson(n.params, sk.defaults);
    if (n.kept) {
      ojson c;
      c["centre"] = {n.kept->centre.x(), n.kept->centre.y(), n.kept->centre.z()};
      c["radius"] = n.kept->radius;
      o["circle"] = std::move(c);
    }
    j["nodes"].push_back(std::move(o));
  }
  return j;
}

/// One top-level key a line, one camera or node a line (diff-friendly, still plain JSON).
std::string layout(const ojson& j) {
  std::string out = "{\n";
  std::size_t k = 0;
  for (auto it = j.begin(); it != j.end(); ++it, ++k) {
    out += "  " + ojson(it.key()).dump() + ": ";
    if (it->is_array() && !it->empty() && it->front().is_object()) {
      out += "[\n";
      for (std::size_t i = 0; i < it->size(); ++i) out += "    " + (*it)[i].dump() + (i + 1 < it->size() ? ",\n" : "\n");
      out += "  ]";
    } else {
      out += it->dump();
    }
    out += k + 1 < j.size() ? ",\n" : "\n";
  }
  return out + "}\n";
}

}  // namespace

sketch::Sketch readSketch(std::istream& in, const std::string& source) {
  return sketchFromJson(parseJson(in, source), source);
}

sketch::Sketch readSketch(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  return readSketch(in, path.string());
}

void writeSketch(std::ostream& out, const sketch::Sketch& sk) {
  sk.validate();
  out << layout(sketchToJson(sk));
  if (!out) throw OutputError("sketch: write failed");
}

void writeSketch(const std::filesystem::path& path, const sketch::Sketch& sk) {
  sk.validate();
  std::string text = layout(sketchToJson(sk));
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

void writeSketch(const std::filesystem::path& path, const sketch::Sketch& sk, const SketchCloudRecord& cloud) {
  sk.validate();
  std::string text = layout(sketchToJson(sk, &cloud));
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

SketchFile readSketchFile(std::istream& in, const std::string& source) {
  const json root = parseJson(in, source);
  SketchFile f;
  f.sketch = sketchFromJson(root, source);
  f.cloud = cloudRecordFromJson(root, source);
  return f;
}

SketchFile readSketchFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  return readSketchFile(in, path.string());
}

std::string cloudContentHash(const geom::PointCloud& cloud) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64-bit offset basis
  for (const geom::Vec3& p : cloud.positions) {
    for (int k = 0; k < 3; ++k) {
      std::uint64_t bits;
      const double v = p[k];
      std::memcpy(&bits, &v, sizeof bits);
      for (int b = 0; b < 8; ++b) {
        h ^= (bits >> (8 * b)) & 0xffu;
        h *= 1099511628211ull;  // FNV prime
      }
    }
  }
  char text[40];
  std::snprintf(text, sizeof text, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return text;
}

SketchCloudRecord makeCloudRecord(const geom::PointCloud& cloud, const std::filesystem::path& cloudPath,
                                  const std::filesystem::path& sketchPath) {
  SketchCloudRecord r;
  r.points = cloud.size();
  r.hash = cloudContentHash(cloud);
  std::error_code ec;
  if (!cloudPath.empty()) {
    const std::filesystem::path dir = std::filesystem::absolute(sketchPath, ec).parent_path();
    const std::filesystem::path abs = std::filesystem::absolute(cloudPath, ec).lexically_normal();
    const std::filesystem::path rel = abs.lexically_relative(dir);
    r.path = (!rel.empty() && !ec ? rel : cloudPath).generic_string();
  }
  return r;
}

geom::Camera readCamera(std::istream& in, const std::string& source) {
  return cameraFromJson(parseJson(in, source), Ctx{source, "camera"});
}

geom::Camera readCamera(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  return readCamera(in, path.string());
}

void writeCamera(std::ostream& out, const geom::Camera& camera) {
  camera.validate("camera");
  out << layout(cameraToJson(camera));
  if (!out) throw OutputError("camera: write failed");
}

void writeCamera(const std::filesystem::path& path, const geom::Camera& camera) {
  camera.validate(path.string());
  std::string text = layout(cameraToJson(camera));
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace treesketch::io
