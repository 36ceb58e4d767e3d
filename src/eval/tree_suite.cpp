#include "treesketch/eval/tree_suite.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "treesketch/gen/branch_mesh.h"
#include "treesketch/gen/skeleton.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {

namespace fs = std::filesystem;
using geom::Vec3;

TreeCase treeCaseFromGenerated(const std::string& name, const gen::GeneratedTree& tree) {
  TreeCase tc;
  tc.name = name;
  tc.branches = tree.branches.mesh;
  tc.leaves = tree.leaves;
  tc.up = tree.skeleton.up;
  tc.woodVolume = gen::branchMeshVolume(tree.skeleton, tree.branches);
  for (const auto& b : tree.skeleton.branches) {
    sketch::BranchPolyline pl;
    std::vector<double> radii;
    for (const auto& s : b.sections) {
      pl.points.push_back(s.centre);
      radii.push_back(s.radius);
    }
    pl.parent = b.parent;
    pl.parentVertex = b.parentSection < 0 ? 0 : static_cast<std::size_t>(b.parentSection);
    tc.axes.push_back(std::move(pl));
    tc.axisRadii.push_back(std::move(radii));
  }
  return tc;
}

std::vector<TreeCase> builtinTrees(int count) {
  static const char* kPresets[] = {"default", "sparse", "conifer"};
  std::vector<TreeCase> trees;
  for (int i = 0; i < count; ++i) {
    std::string preset = kPresets[i % 3];
    gen::TreeOptions options = gen::presetOptions(preset);
    options.seed = static_cast<std::uint64_t>(i + 1);
    trees.push_back(
        treeCaseFromGenerated("builtin_" + preset + "_s" + std::to_string(options.seed), gen::generateTree(options)));
  }
  return trees;
}

namespace {

Vec3 readVec3(const nlohmann::json& j, const std::string& source, const std::string& what) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw InputError(source + ": " + what + ": expected an array of 3 numbers");
  Vec3 v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  if (!v.allFinite()) throw InputError(source + ": " + what + ": not finite");
  return v;
}

nlohmann::json readJsonFile(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open");
  nlohmann::json doc;
  try {
    in >> doc;
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path.string() + ": byte offset " + std::to_string(e.byte) + ": malformed JSON");
  }
  return doc;
}

/// One ez-tree branch's wood: its frustums times its polygon's share of the circle.
double ezTreeBranchVolume(const nlohmann::json& branch, const std::string& source, const std::string& where) {
  const nlohmann::json sides = branch.value("segment_count", nlohmann::json());
  if (!sides.is_number_integer() || sides.get<long long>() < 3 || sides.get<long long>() > 65536)
    throw InputError(source + ": " + where + ".segment_count: expected an integer from 3 to 65536");
  const nlohmann::json sections = branch.value("sections", nlohmann::json());
  if (!sections.is_array()) throw InputError(source + ": " + where + ": expected a 'sections' array");
  double volume = 0, previousRadius = 0;
  Vec3 previousCentre = Vec3::Zero();
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const std::string at = where + ".sections[" + std::to_string(s) + "]";
    if (!sections[s].is_object()) throw InputError(source + ": " + at + ": expected an object");
    const Vec3 centre = readVec3(sections[s].value("center", nlohmann::json()), source, at + ".center");
    const nlohmann::json r = sections[s].value("radius", nlohmann::json());
    if (!r.is_number() || !std::isfinite(r.get<double>()) || r.get<double>() < 0)
      throw InputError(source + ": " + at + ".radius: expected a finite number of at least 0");
    if (s > 0) volume += gen::frustumVolume((centre - previousCentre).norm(), previousRadius, r.get<double>());
    previousCentre = centre;
    previousRadius = r.get<double>();
  }
  return gen::inscribedPolygonShare(static_cast<int>(sides.get<long long>())) * volume;
}

}  // namespace

double readEzTreeWoodVolume(const fs::path& jsonPath) {
  const std::string source = jsonPath.string();
  const nlohmann::json doc = readJsonFile(jsonPath);
  if (!doc.is_object() || !doc.contains("skeleton") || !doc["skeleton"].is_object() ||
      !doc["skeleton"].contains("branches"))
    return std::numeric_limits<double>::quiet_NaN();
  const auto& branches = doc["skeleton"]["branches"];
  if (!branches.is_array()) throw InputError(source + ": skeleton.branches: expected an array");
  double volume = 0;
  for (std::size_t i = 0; i < branches.size(); ++i) {
    const std::string where = "skeleton.branches[" + std::to_string(i) + "]";
    if (!branches[i].is_object()) throw InputError(source + ": " + where + ": expected an object");
    volume += ezTreeBranchVolume(branches[i], source, where);
  }
  return volume;
}

void readEzTreeAxes(const fs::path& jsonPath, std::vector<sketch::BranchPolyline>& axes,
                    std::vector<std::vector<double>>& radii) {
  const std::string source = jsonPath.string();
  const nlohmann::json doc = readJsonFile(jsonPath);
  if (!doc.contains("skeleton") || !doc["skeleton"].contains("limbs") || !doc["skeleton"]["limbs"].is_array())
    throw InputError(source + ": expected an object with skeleton.limbs (ez-tree layout)");
  const auto& limbs = doc["skeleton"]["limbs"];
  axes.clear();
  radii.clear();
  std::vector<int> limbIds;
  for (std::size_t i = 0; i < limbs.size(); ++i) {
    const auto& limb = limbs[i];
    std::string where = "skeleton.limbs[" + std::to_string(i) + "]";
    if (!limb.contains("sections") || !limb["sections"].is_array() || limb["sections"].empty())
      throw InputError(source + ": " + where + ": expected a non-empty 'sections' array");
    sketch::BranchPolyline pl;
    std::vector<double> r;
    for (std::size_t s = 0; s < limb["sections"].size(); ++s) {
      const auto& sec = limb["sections"][s];
      pl.points.push_back(readVec3(sec.value("center", nlohmann::json()), source,
                                   where + ".sections[" + std::to_string(s) + "].center"));
      r.push_back(sec.value("radius", 0.0));
    }
    int parentLimb = -1;
    if (limb.contains("parent_limb") && limb["parent_limb"].is_number_integer()) parentLimb = limb["parent_limb"];
    pl.parent = parentLimb;  // remapped below from limb ids to list indices
    limbIds.push_back(limb.value("id", static_cast<int>(i)));
    axes.push_back(std::move(pl));
    radii.push_back(std::move(r));
  }
  // Map parent limb ids to indices; parent vertex = the parent's section nearest to our start.
  for (auto& pl : axes) {
    if (pl.parent < 0) continue;
    auto it = std::find(limbIds.begin(), limbIds.end(), pl.parent);
    if (it == limbIds.end())
      throw InputError(source + ": a limb names unknown parent limb " + std::to_string(pl.parent));
    pl.parent = static_cast<int>(it - limbIds.begin());
    const auto& parentPts = axes[pl.parent].points;
    std::size_t best = 0;
    double bestD = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < parentPts.size(); ++k) {
      double d = (parentPts[k] - pl.points.front()).squaredNorm();
      if (d < bestD) {
        bestD = d;
        best = k;
      }
    }
    pl.parentVertex = best;
  }
  int roots = static_cast<int>(std::count_if(axes.begin(), axes.end(), [](const auto& a) { return a.parent < 0; }));
  if (roots == 0) throw InputError(source + ": skeleton.limbs has no root limb");
  if (roots > 1) {
    // Several stems from the ground (bushes): hang every extra root on the first one's base so the
    // sketch stays one tree, as a user would draw the stems from a common root node.
    int first = -1;
    for (std::size_t i = 0; i < axes.size(); ++i) {
      if (axes[i].parent >= 0) continue;
      if (first < 0)
        first = static_cast<int>(i);
      else {
        axes[i].parent = first;
        axes[i].parentVertex = 0;
      }
    }
  }
}

std::vector<TreeCase> loadTreeFolder(const fs::path& folder, double metresPerUnit) {
  if (!(metresPerUnit > 0) || !std::isfinite(metresPerUnit))
    throw OptionsError("metres per scene unit must be positive and finite (got " + std::to_string(metresPerUnit) + ")");
  if (!fs::is_directory(folder)) throw InputError(folder.string() + ": not a directory");
  std::vector<fs::path> jsons;
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.path().extension() != ".json") continue;
    fs::path stem = e.path();
    stem.replace_extension("");
    if (fs::exists(stem.string() + ".branches.obj")) jsons.push_back(e.path());
  }
  std::sort(jsons.begin(), jsons.end());
  if (jsons.empty()) throw InputError(folder.string() + ": no <name>.json with a matching <name>.branches.obj");
  std::vector<TreeCase> trees;
  for (const auto& j : jsons) {
    fs::path stem = j;
    stem.replace_extension("");
    TreeCase tc;
    tc.name = stem.filename().string();
    tc.branches = io::readMesh(stem.string() + ".branches.obj");
    if (!(tc.branches.area() > 0))  // nothing to scan or compare with: a data error, named
      throw DegenerateInputError(stem.string() + ".branches.obj: the branch mesh has zero area (its " +
                                 std::to_string(tc.branches.triangles.size()) +
                                 " triangles all have repeated or collinear corners); nothing to scan or compare");
    if (fs::exists(stem.string() + ".leaves.obj")) tc.leaves = io::readMesh(stem.string() + ".leaves.obj");
    tc.up = geom::UpAxis::Y;
    tc.metresPerUnit = metresPerUnit;
    readEzTreeAxes(j, tc.axes, tc.axisRadii);
    tc.woodVolume = readEzTreeWoodVolume(j);
    trees.push_back(std::move(tc));
  }
  return trees;
}

}  // namespace treesketch::eval
