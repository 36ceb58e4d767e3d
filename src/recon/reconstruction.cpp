// Incremental reconstruction: diff the sketch, re-fit changed nodes, re-sweep (thesis §4.4 rebuilt
// everything on every change; here only what depends on the edit).
#include "treesketch/recon/reconstruction.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <map>
#include <set>

namespace treesketch::recon {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

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
  auto t0 = std::chrono::steady_clock::now();
  index_ = std::make_unique<fit::CloudIndex>(cloud, options_.index);
  timings_.indexMs = msSince(t0);
}

void Reconstruction::reset() {
  entries_.clear();
  sweeper_ = sweep::TubeSweeper(options_.sweep);
}

const fit::NodeResult* Reconstruction::result(NodeId id) const {
  auto it = entries_.find(id);
  return it == entries_.end() ? nullptr : &it->second.result;
}

std::map<NodeId, const fit::NodeResult*> Reconstruction::results() const {
  std::map<NodeId, const fit::NodeResult*> out;
  for (const auto& [id, e] : entries_) out[id] = &e.result;
  return out;
}

std::vector<NodeId> Reconstruction::update(const sketch::Sketch& sketch, const ProgressFn& progress) {
  auto t0 = std::chrono::steady_clock::now();
  sketch.validate();
  // 0. Not-wood lassos: recompute the index's exclusions when they changed; every fit may change.
  bool lassosChanged = false;
  if (!sameLassos(notWood_, sketch)) {
    lassosChanged = true;
    notWood_.clear();
    for (const auto& l : sketch.notWood()) notWood_.emplace_back(l, sketch.cameras()[l.camera]);
    if (sketch.notWood().empty())
      index_->setExcluded({});
    else
      index_->setExcluded([&](const geom::Vec3& p) { return sketch.isNotWood(p); });
  }
  // 1. Diff: which nodes have new inputs (geometry or params); drop removed nodes.
  std::vector<NodeId> changed;
  std::vector<Entry> fresh;
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
    changed.push_back(id);
    fresh.push_back(Entry{g, node.params, node.kept, node.parent, {}});
  }
  for (auto it = entries_.begin(); it != entries_.end();)
    it = present.count(it->first) ? std::next(it) : entries_.erase(it);
  // With the depth choice, a screen node's fit depends on its parent's circle (fit::FitPrior):
  // a screen node under a re-fitted node is re-fitted too, after it (waves, parents first).
  const bool priors = options_.fit.chooseDepth;
  std::map<NodeId, std::size_t> slot;  // changed id -> index in `changed`
  for (std::size_t i = 0; i < changed.size(); ++i) slot[changed[i]] = i;
  if (priors) {
    for (NodeId id : sketch.topologicalOrder()) {
      const sketch::Node& node = sketch.node(id);
      if (slot.count(id) || !node.isScreenNode() || node.kept || !slot.count(node.parent)) continue;
      slot[id] = changed.size();
      changed.push_back(id);
      const auto& e = entries_.at(id);
      fresh.push_back(Entry{e.geometry, e.params, e.kept, node.parent, {}});
    }
  }
  std::vector<int> wave(changed.size(), 0);
  int waves = 1;
  if (priors) {
    // `changed` holds parents before children within each pass; levels by parent chains.
    for (bool again = true; again;) {
      again = false;
      for (std::size_t i = 0; i < changed.size(); ++i) {
        auto it = slot.find(fresh[i].parent);
        const int w = it == slot.end() ? 0 : wave[it->second] + 1;
        if (w != wave[i]) {
          wave[i] = w;
          again = true;
        }
      }
    }
    for (int w : wave) waves = std::max(waves, w + 1);
  }

  // 2. Fit the changed nodes (independent: parallel when several); kept circles need no fit.
  auto tFit = std::chrono::steady_clock::now();
  std::atomic<std::uint64_t> done{0};
  const std::uint64_t total = changed.size();
  // The prior is the nearest fitted ancestor's circle (a skipped parent passes its own parent's
  // on: without one, a node would take the front-most circle anywhere along its ray).
  auto priorOf = [&](NodeId parent, fit::FitPrior* out) {
    for (NodeId a = parent; priors && a != sketch::kNoNode; a = sketch.node(a).parent) {
      const fit::NodeResult* r = nullptr;
      if (auto it = slot.find(a); it != slot.end())
        r = &fresh[it->second].result;
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
    Entry& e = fresh[i];
    if (e.kept) {
      e.result = fit::keptCircleResult(e.geometry, e.params, *e.kept);
    } else {
      fit::NodeFitOptions fo = options_.fit;
      fo.circle.seed = options_.seed + std::uint64_t(std::int64_t(changed[i]));
      fit::FitPrior prior;
      const bool hasPrior = e.geometry.hasLine && priorOf(e.parent, &prior);
      e.result = fit::fitNode(*index_, e.geometry, e.params, fo, hasPrior ? &prior : nullptr);
    }
    const std::uint64_t d = ++done;
    if (progress && (d % 64 == 0 || d == total)) progress(d, total);
  };
  for (int w = 0; w < waves; ++w) {
    std::vector<std::size_t> now;
    for (std::size_t i = 0; i < changed.size(); ++i)
      if (wave[i] == w) now.push_back(i);
    if (options_.parallel && now.size() > 1)
      tbb::parallel_for(std::size_t(0), now.size(), [&](std::size_t k) { fitOne(now[k]); });
    else
      for (std::size_t i : now) fitOne(i);
  }
  for (std::size_t i = 0; i < changed.size(); ++i) entries_[changed[i]] = std::move(fresh[i]);
  fitCount_ += changed.size();
  timings_.fitMs = msSince(tFit);

  // 3. Sweep.
  auto tSweep = std::chrono::steady_clock::now();
  std::vector<sweep::SweepNode> nodes;
  nodes.reserve(entries_.size());
  for (const auto& [id, e] : entries_) {
    sweep::SweepNode n;
    n.id = id;
    n.parent = e.parent;
    n.fitted = e.result.status == fit::NodeStatus::Fitted;
    n.disc = {e.result.centre, e.result.normal, e.result.radius};
    nodes.push_back(n);
  }
  sweeper_.update(nodes);
  timings_.sweepMs = msSince(tSweep);
  timings_.totalMs = msSince(t0);
  return changed;
}

ReconstructionResult reconstruct(const geom::PointCloud& cloud, const sketch::Sketch& sketch,
                                 const ReconstructionOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  Reconstruction rec(cloud, options);
  rec.update(sketch);
  ReconstructionResult out = rec.result(sketch);
  out.timings.totalMs = msSince(t0);
  return out;
}

ReconstructionOptions sketchReconstructionOptions() {
  ReconstructionOptions o;
  o.fit.chooseDepth = true;
  return o;
}

ReconstructionResult Reconstruction::result(const sketch::Sketch& sketch) const {
  ReconstructionResult out;
  for (const auto& [id, r] : results()) out.results[id] = *r;
  out.order = sketch.topologicalOrder();
  for (NodeId id : out.order) out.parents[id] = sketch.node(id).parent;
  out.mesh = mesh();
  out.timings = timings();
  return out;
}

}  // namespace treesketch::recon
