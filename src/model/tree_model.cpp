// The one model at the end of every path, and every output written from it (see tree_model.h).
#include "treesketch/model/tree_model.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::model {

namespace {

/// Branch orders from the shape (nodes parents first): at a node, the child with the largest
/// radius continues its branch (the first such on a tie); every other child starts a branch one
/// order up. Roots are order 0.
void assignBranchOrders(std::vector<geom::ModelNode>& nodes) {
  std::vector<std::int64_t> main(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::int64_t p = nodes[i].parent;
    if (p < 0) continue;
    std::int64_t& m = main[static_cast<std::size_t>(p)];
    if (m < 0 || nodes[i].radius > nodes[static_cast<std::size_t>(m)].radius) m = static_cast<std::int64_t>(i);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::int64_t p = nodes[i].parent;
    if (p < 0) {
      nodes[i].branchOrder = 0;
      continue;
    }
    const std::int32_t parentOrder = nodes[static_cast<std::size_t>(p)].branchOrder;
    nodes[i].branchOrder = main[static_cast<std::size_t>(p)] == static_cast<std::int64_t>(i) ? parentOrder
                                                                                              : parentOrder + 1;
  }
}

/// Ids (and measured flags) of the pieces geom::cylinderModelFromNodes makes: one per node with a
/// parent, in node order.
void pieceAttributes(const std::vector<geom::ModelNode>& nodes, const std::vector<std::int64_t>& nodeIds,
                     const std::vector<char>& nodeMeasured, TreeModel* out) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].parent < 0) continue;
    out->ids.push_back(nodeIds[i]);
    out->measured.push_back(nodeMeasured[i]);
  }
}

void writeJson(const std::string& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  writeFileAtomically(
      path, [&](std::ostream& os) { os << text; }, false);
}

}  // namespace

TreeModel fromReconstruction(const recon::ReconstructionResult& r, geom::UpAxis up) {
  std::vector<geom::ModelNode> nodes;
  std::vector<std::int64_t> ids;
  std::map<sketch::NodeId, std::int64_t> index;  // node with a circle → its place in `nodes`
  for (sketch::NodeId id : r.order) {
    const fit::NodeResult& n = r.results.at(id);
    if (n.status != fit::NodeStatus::Fitted || !(n.radius > 0) || !n.centre.allFinite()) continue;
    geom::ModelNode m;
    m.position = n.centre;
    m.radius = n.radius;
    for (sketch::NodeId p = r.parents.at(id); p != sketch::kNoNode; p = r.parents.at(p)) {
      auto it = index.find(p);
      if (it != index.end()) {
        m.parent = it->second;
        break;
      }
    }
    index[id] = static_cast<std::int64_t>(nodes.size());
    nodes.push_back(m);
    ids.push_back(static_cast<std::int64_t>(id));
  }
  assignBranchOrders(nodes);
  TreeModel model;
  model.up = up;
  model.cylinders = geom::cylinderModelFromNodes(nodes);
  pieceAttributes(nodes, ids, std::vector<char>(nodes.size(), 1), &model);
  model.mesh = r.mesh;
  return model;
}

TreeModel fromSkeletonNodes(const std::vector<skeleton::SkeletonNode>& nodes, const std::vector<char>& accepted,
                            geom::UpAxis up) {
  TreeModel model;
  model.up = up;
  model.cylinders = skeleton::cylinderModelFromSkeleton(nodes);
  std::vector<geom::ModelNode> shape(nodes.size());
  std::vector<std::int64_t> ids(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    shape[i].parent = nodes[i].parent;
    ids[i] = static_cast<std::int64_t>(i);
  }
  pieceAttributes(shape, ids, accepted.size() == nodes.size() ? accepted : std::vector<char>(nodes.size(), 1),
                  &model);
  return model;
}

TreeModel fromAutoSkeleton(const skeleton::AutoSkeletonResult& r, geom::UpAxis up) {
  TreeModel model = fromSkeletonNodes(r.model, r.fitAccepted, up);
  model.mesh = r.mesh;
  return model;
}

double measuredVolumeShare(const TreeModel& model) {
  double all = 0, measured = 0;
  for (std::size_t i = 0; i < model.cylinders.size(); ++i) {
    const double v = model.cylinders.cylinders[i].volume();
    all += v;
    if (i < model.measured.size() && model.measured[i]) measured += v;
  }
  return all > 0 ? measured / all : 0.0;
}

std::string ModelMeasures::summary() const {
  return hasFit ? compare::summaryLine(fit) + "; " + compare::summaryLine(figures) : compare::summaryLine(figures);
}

ModelMeasures measure(const TreeModel& model, const geom::PointCloud& cloud, const MeasureOptions& options) {
  ModelMeasures m;
  compare::TreeMetricsOptions mo;
  mo.unitMetres = options.unitMetres;
  m.metrics = compare::treeMetrics(model.cylinders, model.up, mo, &cloud);
  m.figures = compare::modelFigures(model.cylinders, model.up, options.unitMetres);
  m.measuredVolumeShare = measuredVolumeShare(model);
  if (options.fit) {
    compare::ModelFitOptions fo;
    fo.unitMetres = options.unitMetres;
    m.fit = compare::measureModelFit(cloud, model.cylinders, fo);
    m.hasFit = true;
  }
  return m;
}

void checkOutputs(const OutputPaths& paths, const std::vector<std::string>& inputs) {
  const std::vector<const std::string*> outs = paths.all();
  for (const std::string* out : outs) {
    if (out->empty()) continue;
    for (const std::string& in : inputs)
      if (!in.empty()) checkNotAnInput(*out, {in});
    for (const std::string* other : outs)
      if (other != out && !other->empty() && *other == *out)
        throw OptionsError("the same path is given for two outputs: " + *out);
  }
  for (const std::string* out : outs)
    if (!out->empty()) checkOutputWritable(*out);
  if (!paths.mesh.empty()) {
    try {
      io::meshFormatFromPath(paths.mesh);
    } catch (const InputError& e) {
      throw OptionsError(std::string("mesh output: ") + e.what());
    }
  }
}

nlohmann::json reportJson(const ModelMeasures& m, nlohmann::json header) {
  if (!m.hasFit) throw OptionsError("a report needs the model measured against its cloud");
  header["model"] = {{"fit", compare::toJson(m.fit)},
                     {"figures", compare::toJson(m.figures)},
                     {"measuredVolumeShare", m.measuredVolumeShare}};
  header["metrics"] = compare::toJson(m.metrics);
  return header;
}

void writeOutputs(const TreeModel& model, const ModelMeasures& measures, const OutputPaths& paths,
                  const nlohmann::json& reportHeader) {
  if (!paths.cylinders.empty()) io::writeCylinderCsv(paths.cylinders, model.cylinders, model.ids);
  if (!paths.qsm.empty()) io::writeTreeQsmCylinders(paths.qsm, model.cylinders, model.up);
  if (!paths.mesh.empty()) io::writeMesh(paths.mesh, model.mesh);
  if (!paths.metrics.empty()) writeJson(paths.metrics, compare::toJson(measures.metrics));
  if (!paths.report.empty()) writeJson(paths.report, reportJson(measures, reportHeader));
}

}  // namespace treesketch::model
