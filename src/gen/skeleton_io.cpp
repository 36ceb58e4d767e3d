#include "treesketch/gen/skeleton_io.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::gen {

using nlohmann::json;

namespace {

constexpr const char* kFormat = "treesketch-skeleton";
constexpr int kVersion = 1;

json vecToJson(const geom::Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

/// Reads JSON values with error messages that name the source and the JSON path.
class Reader {
 public:
  explicit Reader(const std::string& source) : source_(source) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(source_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }
  const json& field(const json& object, const std::string& path, const char* key) const {
    if (!object.is_object()) fail(path, "expected a JSON object");
    auto it = object.find(key);
    if (it == object.end()) fail(path, std::string("missing field \"") + key + "\"");
    return *it;
  }
  double number(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "expected a number");
    double x = v.get<double>();
    if (!std::isfinite(x)) fail(path, "expected a finite number");
    return x;
  }
  int integer(const json& v, const std::string& path) const {
    if (!v.is_number_integer()) fail(path, "expected an integer");
    auto x = v.get<std::int64_t>();
    if (x < -1 || x > 1000000000) fail(path, "integer out of range [-1, 1e9]");
    return static_cast<int>(x);
  }
  geom::Vec3 vec3(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != 3) fail(path, "expected an array of 3 numbers");
    return {number(v[0], path + "[0]"), number(v[1], path + "[1]"), number(v[2], path + "[2]")};
  }

 private:
  std::string source_;
};

}  // namespace

json skeletonToJson(const Skeleton& skeleton) {
  json branches = json::array();
  for (const SkeletonBranch& b : skeleton.branches) {
    json sections = json::array();
    for (const Section& s : b.sections)
      sections.push_back({{"center", vecToJson(s.centre)}, {"radius", s.radius}, {"axis", vecToJson(s.axis)}});
    branches.push_back({{"id", b.id},
                        {"parent", b.parent},
                        {"parent_section", b.parentSection},
                        {"level", b.level},
                        {"sections", std::move(sections)}});
  }
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["up"] = geom::toString(skeleton.up);
  j["units"] = "m";
  j["branches"] = std::move(branches);
  return j;
}

Skeleton skeletonFromJson(const json& j, const std::string& source) {
  Reader r(source);
  if (!j.is_object()) r.fail("", "expected a JSON object with \"format\": \"treesketch-skeleton\"");
  const json& format = r.field(j, "", "format");
  if (!format.is_string() || format.get<std::string>() != kFormat)
    r.fail("format", std::string("expected \"") + kFormat + "\"");
  const json& version = r.field(j, "", "version");
  if (!version.is_number_integer() || version.get<std::int64_t>() != kVersion)
    r.fail("version", "expected version " + std::to_string(kVersion));
  Skeleton skeleton;
  const json& up = r.field(j, "", "up");
  if (!up.is_string() || (up != "y" && up != "z")) r.fail("up", "expected \"y\" or \"z\"");
  skeleton.up = up == "y" ? geom::UpAxis::Y : geom::UpAxis::Z;
  if (auto it = j.find("units"); it != j.end() && *it != "m") r.fail("units", "expected \"m\"");
  const json& branches = r.field(j, "", "branches");
  if (!branches.is_array()) r.fail("branches", "expected an array");
  for (std::size_t bi = 0; bi < branches.size(); ++bi) {
    const std::string bp = "branches[" + std::to_string(bi) + "]";
    const json& jb = branches[bi];
    SkeletonBranch b;
    b.id = r.integer(r.field(jb, bp, "id"), bp + ".id");
    b.parent = r.integer(r.field(jb, bp, "parent"), bp + ".parent");
    b.parentSection = r.integer(r.field(jb, bp, "parent_section"), bp + ".parent_section");
    b.level = r.integer(r.field(jb, bp, "level"), bp + ".level");
    const json& sections = r.field(jb, bp, "sections");
    if (!sections.is_array()) r.fail(bp + ".sections", "expected an array");
    for (std::size_t si = 0; si < sections.size(); ++si) {
      const std::string sp = bp + ".sections[" + std::to_string(si) + "]";
      Section s;
      s.centre = r.vec3(r.field(sections[si], sp, "center"), sp + ".center");
      s.radius = r.number(r.field(sections[si], sp, "radius"), sp + ".radius");
      s.axis = r.vec3(r.field(sections[si], sp, "axis"), sp + ".axis");
      b.sections.push_back(s);
    }
    skeleton.branches.push_back(std::move(b));
  }
  if (std::string problem = findSkeletonProblem(skeleton); !problem.empty())
    throw InputError(source + ": malformed skeleton: " + problem);
  return skeleton;
}

void writeSkeletonJson(std::ostream& out, const Skeleton& skeleton, bool pretty) {
  out << skeletonToJson(skeleton).dump(pretty ? 1 : -1) << "\n";
  if (!out) throw OutputError("skeleton JSON: the output stream failed");
}

void writeSkeletonJson(const std::filesystem::path& path, const Skeleton& skeleton, bool pretty) {
  writeFileAtomically(path, [&](std::ostream& out) { writeSkeletonJson(out, skeleton, pretty); }, false);
}

Skeleton readSkeletonJson(std::istream& in, const std::string& source) {
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(atOffset(source, e.byte, std::string("expected valid JSON (") + e.what() + ")"));
  } catch (const json::exception& e) {  // e.g. a number too large for a double
    throw InputError(source + ": expected valid JSON with finite numbers (" + e.what() + ")");
  }
  return skeletonFromJson(j, source);
}

Skeleton readSkeletonJson(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the skeleton file");
  return readSkeletonJson(in, path.string());
}

}  // namespace treesketch::gen
