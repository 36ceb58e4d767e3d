// Incremental reconstruction: diff the sketch, re-fit changed nodes, re-sweep (thesis §4.4 rebuilt
// everything on every change; here only what depends on the edit).
#include "treesketch/recon/reconstruction.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <map>
#include <set>

#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::recon {

namespace {

bool sameLassos(const std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>>& a, const sketch::Sketch& sk) {
  if (a.size() != sk.notWood().size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const sketch::NotWoodLasso& l = sk.notWood()[i];
    const geom::Camera& c = sk.cameras()[l.camera];
    const geom::Camera& d = a[i].second;
    if (!(a[i].first.polygon == l.polygon) || !(c.view == d.view) || !(c.projection == d.projection) ||
        c.viewport.x != d.viewport.x || c.viewport.y != d.viewport.y || c.viewport.width != d.viewport.width ||
        c.viewport.height != d.viewport.height)
      return false;
  }
  return true;
}

}  // namespace

Reconstruction::Reconstruction(const geom::PointCloud& cloud, const ReconstructionOptions& options)
    : options_(options), sweeper_(options.sweep) {
  const Stopwatch timer;
  index_ = std::make_unique<fit::CloudIndex>(cloud, options_.index);
  cloudSize_ = cloud.size();
  timings_.indexMs = timer.ms();
}

void Reconstruction::reset() {
  entries_.clear();
  radii_.clear();
  sweeper_ = sweep::TubeSweeper(options_.sweep);
}

const fit::NodeResult* Reconstruction::result(NodeId id) const {
  auto it = entries_.find(id);
  return it == entries_.end() ? nullptr : &it->second.result;
}

const NodeRadius* Reconstruction::radius(NodeId id) const {
  auto it = radii_.find(id);
  return it == radii_.end() ? nullptr : &it->second;
}

std::map<NodeId, const fit::NodeResult*> Reconstruction::results() const {
  std::map<NodeId, const fit::NodeResult*> out;
  for (const auto& [id, e] : entries_) out[id] = &e.result;
  return out;
}

void Reconstruction::setLeafPoints(std::vector<std::uint8_t> leaf) {
  if (!leaf.empty() && leaf.size() != cloudSize_)
    throw OptionsError("leaf points: " + std::to_string(leaf.size()) + " flags for a cloud of " +
                       std::to_string(cloudSize_) + " points");
  if (leaf == leaf_) return;
  leaf_ = std::move(leaf);
  leafChanged_ = true;
}

// 0. Not-wood and wood lassos, and the points classified leaf: recompute the index's exclusions
// when they changed; every fit may change.
bool Reconstruction::refreshExclusions(const sketch::Sketch& sketch) {
  if (sameLassos(notWood_, sketch) && !leafChanged_) return false;
  leafChanged_ = false;
  notWood_.clear();
  for (const auto& l : sketch.notWood()) notWood_.emplace_back(l, sketch.cameras()[l.camera]);
  if (sketch.notWood().empty() && leaf_.empty()) {
    index_->setExcluded({});
  } else if (leaf_.empty()) {
    index_->setExcluded([&](const geom::Vec3& p) { return sketch.isNotWood(p); });
  } else {
    index_->setExcludedByIndex([&](std::uint32_t i, const geom::Vec3& p) {
      const sketch::Sketch::LassoClass c = sketch.lassoClass(p);
      return c == sketch::Sketch::LassoClass::None ? leaf_[i] != 0 : c == sketch::Sketch::LassoClass::NotWood;
    });
  }
  return true;
}

// 1. Diff: which nodes have new inputs (geometry or params); drop removed nodes.
Reconstruction::Pending Reconstruction::diff(const sketch::Sketch& sketch, bool lassosChanged) {
  Pending p;
  std::set<NodeId> present;
  for (NodeId id : sketch.topologicalOrder()) {
    present.insert(id);
    const sketch::Node& node = sketch.node(id);
    sketch::NodeGeometry g = sketch.geometry(id);
    auto it = entries_.find(id);
    if (it != entries_.end() && it->second.geometry == g && it->second.params == node.params &&
        it->second.kept == node.kept && !(lassosChanged && !node.kept)) {
      it->second.parent = node.parent;
      continue;
    }
    p.changed.push_back(id);
    p.fresh.push_back(Entry{g, node.params, node.kept, node.parent, {}});
  }
  for (auto it = entries_.begin(); it != entries_.end();)
    it = present.count(it->first) ? std::next(it) : entries_.erase(it);
  for (std::size_t i = 0; i < p.changed.size(); ++i) p.slot[p.changed[i]] = i;
  p.wave.assign(p.changed.size(), 0);
  return p;
}

// With the depth choice, a screen node's fit depends on its parent's circle (fit::FitPrior): a
// screen node under a re-fitted node is re-fitted too, after it (waves, parents first).
void Reconstruction::addPriorDependents(const sketch::Sketch& sketch, Pending& p) const {
  for (NodeId id : sketch.topologicalOrder()) {
    const sketch::Node& node = sketch.node(id);
    if (p.slot.count(id) || !node.isScreenNode() || node.kept || !p.slot.count(node.parent)) continue;
    p.slot[id] = p.changed.size();
    p.changed.push_back(id);
    const auto& e = entries_.at(id);
    p.fresh.push_back(Entry{e.geometry, e.params, e.kept, node.parent, {}});
  }
  p.wave.assign(p.changed.size(), 0);
  // `changed` holds parents before children within each pass; levels by parent chains.
  for (bool again = true; again;) {
    again = false;
    for (std::size_t i = 0; i < p.changed.size(); ++i) {
      auto it = p.slot.find(p.fresh[i].parent);
      const int w = it == p.slot.end() ? 0 : p.wave[it->second] + 1;
      if (w != p.wave[i]) {
        p.wave[i] = w;
        again = true;
      }
    }
  }
  for (int w : p.wave) p.waves = std::max(p.waves, w + 1);
}

// 2. Fit the changed nodes (independent: parallel when several); kept circles need no fit.
void Reconstruction::fitPending(const sketch::Sketch& sketch, Pending& p, const ProgressFn& progress) {
  const bool priors = options_.fit.chooseDepth;
  std::atomic<std::uint64_t> done{0};
  const std::uint64_t total = p.changed.size();
  // The prior is the nearest fitted ancestor's circle (a skipped parent passes its own parent's
  // on: without one, a node would take the front-most circle anywhere along its ray).
  auto priorOf = [&](NodeId parent, fit::FitPrior* out) {
    for (NodeId a = parent; priors && a != sketch::kNoNode; a = sketch.node(a).parent) {
      const fit::NodeResult* r = nullptr;
      if (auto it = p.slot.find(a); it != p.slot.end())
        r = &p.fresh[it->second].result;
      else if (auto e = entries_.find(a); e != entries_.end())
        r = &e->second.result;
      if (r && r->status == fit::NodeStatus::Fitted && r->radius > 0) {
        *out = fit::FitPrior{r->centre, r->radius};
        return true;
      }
    }
    return false;
  };
  auto fitOne = [&](std::size_t i) {
    Entry& e = p.fresh[i];
    if (e.kept) {
      e.result = fit::keptCircleResult(e.geometry, e.params, *e.kept);
    } else {
      fit::NodeFitOptions fo = options_.fit;
      fo.circle.seed = options_.seed + std::uint64_t(std::int64_t(p.changed[i]));
      fit::FitPrior prior;
      const bool hasPrior = e.geometry.hasLine && priorOf(e.parent, &prior);
      e.result = fit::fitNode(*index_, e.geometry, e.params, fo, hasPrior ? &prior : nullptr);
    }
    const std::uint64_t d = ++done;
    if (progress && (d % 64 == 0 || d == total)) progress(d, total);
  };
  for (int w = 0; w < p.waves; ++w) {
    std::vector<std::size_t> now;
    for (std::size_t i = 0; i < p.changed.size(); ++i)
      if (p.wave[i] == w) now.push_back(i);
    if (options_.parallel && now.size() > 1)
      tbb::parallel_for(std::size_t(0), now.size(), [&](std::size_t k) { fitOne(now[k]); });
    else
      for (std::size_t i : now) fitOne(i);
  }
  for (std::size_t i = 0; i < p.changed.size(); ++i) entries_[p.changed[i]] = std::move(p.fresh[i]);
  fitCount_ += p.changed.size();
}

// 3. The model's circles: fits checked against their limb, radii inferred for the rest.
void Reconstruction::refreshRadii() {
  std::vector<RadiusInput> in;
  in.reserve(order_.size());
  for (NodeId id : order_) {
    auto it = entries_.find(id);
    if (it == entries_.end()) continue;
    in.push_back(RadiusInput{id, it->second.parent, &it->second.result, it->second.geometry,
                             it->second.params.sliceHalfThickness});
  }
  radii_ = inferRadii(in, options_.radii);
}

// 4. Sweep through the model's circles (a node with none is bridged).
void Reconstruction::sweepEntries() {
  std::vector<sweep::SweepNode> nodes;
  nodes.reserve(entries_.size());
  for (const auto& [id, e] : entries_) {
    sweep::SweepNode n;
    n.id = id;
    n.parent = e.parent;
    const NodeRadius* c = radius(id);
    n.fitted = c && c->source != RadiusSource::None;
    if (n.fitted) n.disc = {c->centre, c->normal, c->radius};
    nodes.push_back(n);
  }
  sweeper_.update(nodes);
}

std::vector<NodeId> Reconstruction::fit(const sketch::Sketch& sketch, const ProgressFn& progress) {
  const Stopwatch timer;
  sketch.validate();
  const bool lassosChanged = refreshExclusions(sketch);
  Pending pending = diff(sketch, lassosChanged);
  if (options_.fit.chooseDepth) addPriorDependents(sketch, pending);
  fitPending(sketch, pending, progress);
  order_ = sketch.topologicalOrder();
  refreshRadii();
  timings_.fitMs = timer.ms();
  timings_.sweepMs = 0.0;
  timings_.totalMs = timings_.fitMs;
  return std::move(pending.changed);
}

std::vector<NodeId> Reconstruction::update(const sketch::Sketch& sketch, const ProgressFn& progress) {
  const Stopwatch timer;
  std::vector<NodeId> changed = fit(sketch, progress);
  const Stopwatch sweepTimer;
  sweepEntries();
  timings_.sweepMs = sweepTimer.ms();
  timings_.totalMs = timer.ms();
  return changed;
}

ReconstructionResult reconstruct(const geom::PointCloud& cloud, const sketch::Sketch& sketch,
                                 const ReconstructionOptions& options) {
  const Stopwatch timer;
  Reconstruction rec(cloud, options);
  rec.update(sketch);
  ReconstructionResult out = rec.result(sketch);
  out.timings.totalMs = timer.ms();
  return out;
}

ReconstructionOptions sketchReconstructionOptions() {
  ReconstructionOptions o;
  o.fit.chooseDepth = true;
  o.radii.enabled = true;
  return o;
}

ReconstructionResult Reconstruction::result(const sketch::Sketch& sketch) const {
  ReconstructionResult out;
  for (const auto& [id, r] : results()) out.results[id] = *r;
  out.radii = radii_;
  out.order = sketch.topologicalOrder();
  for (NodeId id : out.order) out.parents[id] = sketch.node(id).parent;
  out.mesh = mesh();
  out.timings = timings();
  return out;
}

}  // namespace treesketch::recon
