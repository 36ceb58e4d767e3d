// The simulated correcting user (see correcting_user.h).
#include "treesketch/eval/correcting_user.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "treesketch/accel/closest_point.h"
#include "treesketch/edit/correction_tools.h"
#include "treesketch/eval/svg_plot.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::eval {

namespace fs = std::filesystem;
using geom::Vec2;
using geom::Vec3;
using sketch::NodeId;

namespace {

const geom::Viewport kViewport{0, 0, 1280, 800};

/// The front view turned about the up axis through the cloud's centre by `deg` (the person walks
/// around the tree: 0 front, 90 side, 180 back, 270 other side).
geom::Camera viewAround(const geom::BBox& bounds, geom::UpAxis up, double deg) {
  geom::Camera cam = geom::presetCamera(geom::PresetView::Front, bounds, up, kViewport, false);
  const Vec3 c = bounds.centre();
  const Eigen::AngleAxisd rot(deg * M_PI / 180.0, geom::upVector(up));
  geom::Mat4 m = geom::Mat4::Identity();
  m.block<3, 3>(0, 0) = rot.toRotationMatrix();
  m.block<3, 1>(0, 3) = c - rot.toRotationMatrix() * c;
  cam.view = cam.view * m;
  return cam;
}

const char* viewName(int v) {
  static const char* names[] = {"front", "side", "back", "other side"};
  return names[v];
}

/// A reference limb resampled: axis points, radii, arc step.
struct LimbSamples {
  std::vector<Vec3> points;
  std::vector<double> radii;
  double step = 0;
};

LimbSamples sampleLimb(const sketch::BranchPolyline& axis, const std::vector<double>& radii, double step) {
  LimbSamples s;
  s.step = step;
  const auto& p = axis.points;
  if (p.size() < 2) return s;
  auto radiusAt = [&](std::size_t i) { return i < radii.size() ? radii[i] : (radii.empty() ? 0.0 : radii.back()); };
  s.points.push_back(p[0]);
  s.radii.push_back(radiusAt(0));
  double carry = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double len = (p[i] - p[i - 1]).norm();
    double t = step - carry;
    while (t <= len) {
      const double f = len > 0 ? t / len : 0;
      s.points.push_back(p[i - 1] + f * (p[i] - p[i - 1]));
      s.radii.push_back((1 - f) * radiusAt(i - 1) + f * radiusAt(i));
      t += step;
    }
    carry = len - (t - step);
  }
  return s;
}

struct Candidate {
  enum class Kind { Stroke, DeleteSubtree, DeleteNode } kind = Kind::Stroke;
  double score = 0;
  std::size_t limb = 0;
  std::size_t from = 0, to = 0;  ///< stroke: sample range on the limb
  NodeId node = sketch::kNoNode;
  std::size_t subtreeSize = 0;
};

// Per-subtree sums over a sketch (bottom-up): the wrong nodes' summed score, the subtree's tube
// surface, its wrong share and its node count.
struct SubtreeSums {
  std::map<NodeId, double> sumW, areaAll, areaW;
  std::map<NodeId, std::size_t> count;
};

SubtreeSums subtreeSums(const sketch::Sketch& sk, const std::vector<NodeId>& order,
                        const std::map<NodeId, double>& wrong, const std::map<NodeId, double>& area) {
  SubtreeSums t;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const NodeId id = *it;
    auto w = wrong.find(id);
    auto ar = area.find(id);
    const double aId = ar != area.end() ? ar->second : 0.0;
    t.sumW[id] += w != wrong.end() ? w->second : 0.0;
    t.areaAll[id] += aId;
    t.areaW[id] += w != wrong.end() ? aId : 0.0;
    t.count[id] += 1;
    const NodeId parent = sk.node(id).parent;
    if (parent != sketch::kNoNode) {
      t.sumW[parent] += t.sumW[id];
      t.areaAll[parent] += t.areaAll[id];
      t.areaW[parent] += t.areaW[id];
      t.count[parent] += t.count[id];
    }
  }
  return t;
}

// One simulated person correcting one automatic model: looks for what is visibly wrong, makes the
// edit that removes the most error, looks at the result and undoes an edit that made it worse.
class CorrectingSession {
 public:
  // `cloud` is the whole scan, also when `automatic` is the model of its classified wood: its nodes
  // carry kept circles (fitted on the wood), so the rebuild reproduces that model and re-fits only
  // what an edit adds; a stroke picks its depth among, and fits its nodes on, every point, as the
  // person sees the whole cloud and draws over the limbs the classifier called leaf. (With the
  // leaf points left out, as the viewer's strokes are once the cloud is classified, such a limb
  // has no points: the person would first lasso it as wood; that lasso is taken as part of the
  // stroke here.)
  CorrectingSession(const TreeCase& tree, const geom::PointCloud& cloud, const sketch::Sketch& automatic,
                    const CorrectingUserOptions& o, const std::string& startLabel)
      : tree_(tree),
        cloud_(cloud),
        o_(o),
        diag_(tree.branches.bounds().diagonal()),
        tol_(o.tolerancePct / 100.0 * diag_),
        rec_(cloud, reconOptions(o)),
        sk_(automatic) {
    run_.tree = tree.name;
    rec_.update(sk_);
    record(0, startLabel, 0.0);
    reference_ = std::make_unique<accel::MeshClosestPoint>(tree.branches);
    const geom::BBox bounds = cloud.bounds();
    for (double deg : {0.0, 90.0, 180.0, 270.0}) views_.push_back(viewAround(bounds, tree.up, deg));
    pickers_.resize(views_.size());
    step_ = 0.004 * diag_;
    for (std::size_t i = 0; i < tree.axes.size(); ++i)
      limbs_.push_back(
          sampleLimb(tree.axes[i], i < tree.axisRadii.size() ? tree.axisRadii[i] : std::vector<double>{}, step_));
    rng_.seed(o.seed * 7919 + 17);
    jitter_ = std::normal_distribution<double>(0.0, o.pixelNoise);
  }

  CorrectingRun run() {
    for (int edit = 1; edit <= o_.maxEdits; ++edit) {
      if (o_.stopAtTarget && run_.editsToTarget >= 0) break;
      const Stopwatch timer;
      std::vector<Candidate> cands;
      addMissedLimbs(cands);
      addWrongTubes(cands);
      if (cands.empty()) break;  // nothing visibly wrong is left
      std::sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });

      const sketch::Sketch saved = sk_;  // for the undo of an edit that made things worse
      NodeId deleted = sketch::kNoNode;
      const std::string action = applyFirstEdit(cands, deleted);
      if (action.empty()) break;
      rec_.update(sk_);
      record(edit, action, timer.ms());
      undoIfWorse(edit, saved, deleted);
    }
    return std::move(run_);
  }

 private:
  static recon::ReconstructionOptions reconOptions(const CorrectingUserOptions& o) {
    recon::ReconstructionOptions ro;
    ro.seed = o.seed;
    ro.fit.chooseDepth = true;  // as the viewer
    ro.radii.enabled = true;
    return ro;
  }

  double pct(double v) const { return diag_ > 0 ? 100.0 * v / diag_ : NAN; }

  void record(int edit, const std::string& action, double ms) {
    CorrectingStep s;
    s.edit = edit;
    s.action = action;
    s.nodes = static_cast<int>(sk_.size());
    DirectionStats b = oneWayDistance(rec_.mesh(), tree_.branches, o_.distance);
    DirectionStats f = oneWayDistance(tree_.branches, rec_.mesh(), o_.distance);
    s.backwardRms = pct(b.rms);
    s.forwardRms = pct(f.rms);
    s.ms = ms;
    run_.steps.push_back(s);
    if (run_.editsToTarget < 0 && s.backwardRms <= o_.targetPct && s.forwardRms <= o_.targetPct)
      run_.editsToTarget = edit;
  }

  const edit::ViewPicker& picker(std::size_t v) {
    if (!pickers_[v]) pickers_[v] = std::make_unique<edit::ViewPicker>(cloud_, views_[v]);
    return *pickers_[v];
  }

  // Missed limbs: axis samples farther than the tolerance outside the model's surface.
  void addMissedLimbs(std::vector<Candidate>& cands) const {
    const accel::MeshClosestPoint model(rec_.mesh());
    for (std::size_t l = 0; l < limbs_.size(); ++l) {
      if (failedLimbs_.count(l) || limbs_[l].points.size() < 2) continue;
      const auto hits = model.queryAll(limbs_[l].points);
      Candidate c;
      c.kind = Candidate::Kind::Stroke;
      c.limb = l;
      bool any = false;
      for (std::size_t k = 0; k < hits.size(); ++k) {
        const double d = std::min(hits[k].distance, diag_);
        const double excess = d - limbs_[l].radii[k];
        if (excess <= tol_) continue;
        if (!any) c.from = k;
        any = true;
        c.to = k;
        c.score += excess * excess * std::max(limbs_[l].radii[k], 1e-3 * diag_) * step_;
      }
      if (any && c.to > c.from) cands.push_back(c);
    }
  }

  // Every node's tube as the model sweeps it: its circle, fitted, kept or inferred from its limb.
  // A stroke's nodes that found no circle of their own (a limb among leaves) have tubes of
  // inferred radius that edit::nodeAnchors leaves at radius 0; the person sees those tubes too.
  std::map<NodeId, edit::NodeAnchor> modelTubes() const {
    std::map<NodeId, edit::NodeAnchor> tubes = edit::nodeAnchors(sk_, &rec_);
    for (auto& [id, a] : tubes) {
      const recon::NodeRadius* r = rec_.radius(id);
      if (r && r->source != recon::RadiusSource::None && r->radius > 0) a = edit::NodeAnchor{r->centre, r->radius};
    }
    return tubes;
  }

  // Wrong tubes: nodes whose circle lies farther than the tolerance outside the reference.
  void addWrongTubes(std::vector<Candidate>& cands) const {
    const auto anchors = modelTubes();
    std::map<NodeId, double> wrong;  // node -> its score
    std::map<NodeId, double> area;   // node -> its tube's surface, radius x spacing (a proxy)
    for (const auto& [id, a] : anchors) {
      if (!(a.radius > 0)) continue;
      const NodeId parent = sk_.node(id).parent;
      double spacing = 2.0 * a.radius;
      if (auto it = anchors.find(parent); it != anchors.end()) spacing = (a.centre - it->second.centre).norm();
      area[id] = a.radius * std::max(spacing, step_);
      const double excess = reference_->query(a.centre).distance - a.radius;
      if (excess <= tol_) continue;
      wrong[id] = excess * excess * area[id];
    }
    // Per subtree (bottom-up): the wrong nodes' summed score, and the share of the subtree's
    // tube surface that is wrong. A person deletes a subtree whose surface is mostly wrong
    // (subtreeWrongShare) — the one that removes the most error — or a lone wrong node.
    const std::vector<NodeId> order = sk_.topologicalOrder();
    SubtreeSums t = subtreeSums(sk_, order, wrong, area);
    std::set<NodeId> covered;  // nodes inside a candidate subtree (parents come first in `order`)
    for (NodeId id : order) {
      const NodeId parent = sk_.node(id).parent;
      if (parent != sketch::kNoNode && covered.count(parent)) covered.insert(id);
      if (id == sk_.root() || failedNodes_.count(id) || !(t.sumW[id] > 0)) continue;
      if (!(t.areaW[id] >= o_.subtreeWrongShare * t.areaAll[id]) || t.count[id] < 2) continue;
      covered.insert(id);
      Candidate c;
      c.kind = Candidate::Kind::DeleteSubtree;
      c.node = id;
      c.score = t.sumW[id];
      c.subtreeSize = t.count[id];
      cands.push_back(c);
    }
    for (const auto& [id, score] : wrong) {
      if (covered.count(id) || failedNodes_.count(id)) continue;
      Candidate c;
      c.kind = Candidate::Kind::DeleteNode;
      c.node = id;
      c.score = score;
      c.subtreeSize = 1;
      cands.push_back(c);
    }
  }

  // Makes the first candidate edit that can be made; returns what it did (empty: none could).
  std::string applyFirstEdit(const std::vector<Candidate>& cands, NodeId& deleted) {
    for (const Candidate& c : cands) {
      if (c.kind != Candidate::Kind::Stroke) {
        deleted = c.node;
        if (c.kind == Candidate::Kind::DeleteSubtree) {
          sketch::deleteSubtree(sk_, c.node);
          return "delete subtree " + std::to_string(c.node) + " (" + std::to_string(c.subtreeSize) + " nodes)";
        }
        try {
          sk_.removeNode(c.node, false);
        } catch (const OptionsError&) {
          failedNodes_.insert(c.node);
          continue;
        }
        return "delete node " + std::to_string(c.node);
      }
      std::string action = strokeLimb(c);
      if (!action.empty()) return action;
    }
    return {};
  }

  // The view where samples a..b of the limb are longest on screen and least hidden (-1: none).
  int bestStrokeView(const LimbSamples& limb, std::size_t a, std::size_t b, double& bestScore) {
    int bestView = -1;
    bestScore = 0;
    for (std::size_t v = 0; v < views_.size(); ++v) {
      const edit::ViewPicker& pk = picker(v);
      double len = 0, visible = 0;
      Vec2 prev = Vec2::Zero();
      int n = 0;
      for (std::size_t k = a; k <= b; ++k) {
        const Vec3 s = views_[v].project(limb.points[k]);
        if (!s.allFinite()) continue;
        if (n > 0) len += (s.head<2>() - prev).norm();
        prev = s.head<2>();
        ++n;
        const double depth = pk.depthOf(limb.points[k]);
        int inFront = 0;
        for (const auto& cand : pk.near(s.head<2>(), 3.0))
          if (cand.depth < depth - limb.radii[k] - tol_) ++inFront;
        visible += inFront < 3;
      }
      const double score = n > 0 ? len * visible / n : 0;
      if (score > bestScore) {
        bestScore = score;
        bestView = int(v);
      }
    }
    return bestView;
  }

  // The stroke: from the last covered sample before the miss (where the person starts, on the
  // model) to the miss's end, in the view where it is longest on screen and least hidden. Returns
  // what was drawn (empty: the limb cannot be drawn; it is not tried again).
  std::string strokeLimb(const Candidate& c) {
    const LimbSamples& limb = limbs_[c.limb];
    const std::size_t a = c.from > 0 ? c.from - 1 : 0, b = c.to;
    double bestScore = 0;
    const int bestView = bestStrokeView(limb, a, b, bestScore);
    if (bestView < 0 || bestScore < 4.0) {  // under 4 visible pixels: nobody sees it
      failedLimbs_.insert(c.limb);
      return {};
    }
    std::vector<Vec2> stroke;
    Vec2 last(NAN, NAN);
    for (std::size_t k = a; k <= b; ++k) {
      const Vec2 s = views_[bestView].project(limb.points[k]).head<2>();
      if (k != a && k != b && (s - last).norm() < 5.0) continue;  // a hand's polyline: ~5 px apart
      stroke.push_back(s + Vec2(jitter_(rng_), jitter_(rng_)));
      last = s;
    }
    failedLimbs_.insert(c.limb);  // one stroke per limb: a person does not redraw the same limb
    try {
      const edit::StrokeResult r = edit::drawLimb(sk_, picker(bestView), cloud_, stroke, edit::nodeAnchors(sk_, &rec_));
      char buf[160];
      std::snprintf(buf, sizeof buf, "stroke limb %zu (%s view, %zu nodes under node %d%s)", c.limb, viewName(bestView),
                    r.added.size(), r.attachedTo, r.depthJumps ? ", depth jumps" : "");
      return buf;
    } catch (const OptionsError&) {
      return {};
    }
  }

  // The person looks at the result: an edit that made the model worse (the two RMS distances' sum
  // grew) is undone. It still counts as an edit (the effort was spent); the curve shows the undone
  // state.
  void undoIfWorse(int edit, const sketch::Sketch& saved, NodeId deleted) {
    const CorrectingStep& now = run_.steps.back();
    const CorrectingStep& before = run_.steps[run_.steps.size() - 2];
    if (now.backwardRms + now.forwardRms > before.backwardRms + before.forwardRms) {
      sk_ = saved;
      rec_.update(sk_);
      if (deleted != sketch::kNoNode) failedNodes_.insert(deleted);
      CorrectingStep undone = before;
      undone.edit = now.edit;
      undone.action = now.action + " — worse, undone";
      undone.ms = now.ms;
      run_.steps.back() = undone;
      if (run_.editsToTarget == edit) run_.editsToTarget = -1;
    }
  }

  const TreeCase& tree_;
  const geom::PointCloud& cloud_;
  const CorrectingUserOptions& o_;
  const double diag_;
  const double tol_;
  recon::Reconstruction rec_;
  sketch::Sketch sk_;
  CorrectingRun run_;
  std::unique_ptr<accel::MeshClosestPoint> reference_;
  std::vector<geom::Camera> views_;
  std::vector<std::unique_ptr<edit::ViewPicker>> pickers_;
  double step_ = 0;
  std::vector<LimbSamples> limbs_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> jitter_;
  std::set<std::size_t> failedLimbs_;
  std::set<NodeId> failedNodes_;
};

}  // namespace

CorrectingRun runCorrectingUser(const TreeCase& tree, const geom::PointCloud& cloud, const sketch::Sketch& automatic,
                                const CorrectingUserOptions& o, const std::string& startLabel) {
  return CorrectingSession(tree, cloud, automatic, o, startLabel).run();
}

std::vector<CorrectingRun> runCorrectingEvaluation(const std::vector<TreeCase>& trees, const EvalOptions& eo,
                                                   const CorrectingUserOptions& o) {
  std::vector<CorrectingRun> runs;
  const std::vector<ScanCondition> conditions = evaluationConditions(eo);
  for (const auto& tree : trees) {
    for (const auto& c : conditions) {
      for (int leafState = 0; leafState < 2; ++leafState) {
        const bool leafOn = leafState == 0;
        if ((leafOn && !(eo.leafOn && c.leafOn)) || (!leafOn && !(eo.leafOff && c.leafOff))) continue;
        const Stopwatch timer;
        TreeScan scan = scanTree(tree, c, leafOn, eo.seed);
        bool onWood = false;
        skeleton::AutoSkeletonResult automatic =
            automaticModel(scan.cloud, leafOn, o.leafOnWoodOnly, tree.up, eo, &onWood);
        CorrectingUserOptions co = o;
        co.distance.minSamples = eo.minSamples;
        co.distance.samples = eo.samples;
        co.distance.seed = eo.seed;
        CorrectingRun r =
            runCorrectingUser(tree, scan.cloud, automatic.sketch, co,
                              onWood ? "start (automatic model of the classified wood)" : "start (automatic model)");
        r.condition = c.name;
        r.pattern = c.pattern;
        r.leaf = leafOn ? "leaf-on" : "leaf-off";
        if (eo.log) {
          const CorrectingStep& first = r.steps.front();
          const CorrectingStep& last = r.steps.back();
          char buf[320];
          std::snprintf(buf, sizeof buf,
                        "%s %s %s correcting user: RMS back/fwd %.3f/%.3f %% -> %.3f/%.3f %% after %d edits; "
                        "edits to %.2f %%: %d  (%.0f s)",
                        tree.name.c_str(), c.name.c_str(), r.leaf.c_str(), first.backwardRms, first.forwardRms,
                        last.backwardRms, last.forwardRms, last.edit, o.targetPct, r.editsToTarget, timer.seconds());
          eo.log(buf);
        }
        runs.push_back(std::move(r));
      }
    }
  }
  return runs;
}

namespace {

/// Edits until both RMS are <= `target` (-1: never within the run).
int editsTo(const CorrectingRun& r, double target) {
  for (const auto& s : r.steps)
    if (s.backwardRms <= target && s.forwardRms <= target) return s.edit;
  return -1;
}

/// The RMS after `edit` edits (a run that stopped earlier keeps its last values).
const CorrectingStep& after(const CorrectingRun& r, int edit) {
  const CorrectingStep* s = &r.steps.front();
  for (const auto& x : r.steps)
    if (x.edit <= edit) s = &x;
  return *s;
}

std::string f3(double v) {
  if (!std::isfinite(v)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

std::string edits(int n, int max) { return n < 0 ? "> " + std::to_string(max) : std::to_string(n); }

}  // namespace

std::string correctingMarkdown(const std::vector<CorrectingRun>& runs, const CorrectingUserOptions& o) {
  std::ostringstream s;
  s << "# Simulated correcting user\n\n"
    << "From the automatic skeleton's sketch, the simulated person makes one edit at a time on the worst visible "
       "error (a stroke along a missed reference limb in the view where it shows best, with "
    << o.pixelNoise << " px hand jitter; deleting a wrong subtree or node), with the viewer's correction tools. "
    << (o.leafOnWoodOnly ? "Leaf-on, it starts from the automatic model of the points the wood/leaf classification "
                           "calls wood (leaf-off settings, as `reconstruct --auto --leaf-on --wood-only`); its strokes "
                           "and rebuilds use every point. "
                         : "Leaf-on, it starts from the automatic model of every point (leaf-on settings). ")
    << "RMS distances are % of the reference diagonal (backward: model to reference; forward: reference to model). "
    << "Error tolerance " << o.tolerancePct << " %; at most " << o.maxEdits << " edits.\n\n";
  s << "| tree | condition | leaf | start back / fwd % | after 5 | after " << o.maxEdits
    << " | edits to 0.6 % | edits to 0.5 % | edits to 0.25 % |\n|---|---|---|---|---|---|---:|---:|---:|\n";
  for (const auto& r : runs) {
    const auto& a = r.steps.front();
    const auto& b = after(r, 5);
    const auto& c = after(r, o.maxEdits);
    s << "| " << r.tree << " | " << r.condition << " | " << r.leaf << " | " << f3(a.backwardRms) << " / "
      << f3(a.forwardRms) << " | " << f3(b.backwardRms) << " / " << f3(b.forwardRms) << " | " << f3(c.backwardRms)
      << " / " << f3(c.forwardRms) << " | " << edits(editsTo(r, 0.6), o.maxEdits) << " | "
      << edits(editsTo(r, 0.5), o.maxEdits) << " | " << edits(editsTo(r, 0.25), o.maxEdits) << " |\n";
  }
  s << "\nMeans over the trees (RMS after the edits; cases reaching the target):\n\n"
    << "| leaf | pattern | cases | start back / fwd % | after 5 | after " << o.maxEdits
    << " | reach 0.6 % | reach 0.5 % | reach 0.25 % |\n|---|---|---:|---|---|---|---:|---:|---:|\n";
  for (const char* leaf : {"leaf-on", "leaf-off"})
    for (const char* pattern : {"sphere", "tls"}) {
      std::vector<const CorrectingRun*> sel;
      for (const auto& r : runs)
        if (r.leaf == leaf && r.pattern == pattern) sel.push_back(&r);
      if (sel.empty()) continue;
      auto mean = [&](int edit, bool backward) {
        double sum = 0;
        for (const auto* r : sel) sum += backward ? after(*r, edit).backwardRms : after(*r, edit).forwardRms;
        return sum / sel.size();
      };
      auto reach = [&](double t) {
        int n = 0;
        for (const auto* r : sel) n += editsTo(*r, t) >= 0;
        return std::to_string(n) + "/" + std::to_string(sel.size());
      };
      s << "| " << leaf << " | " << pattern << " | " << sel.size() << " | " << f3(mean(0, true)) << " / "
        << f3(mean(0, false)) << " | " << f3(mean(5, true)) << " / " << f3(mean(5, false)) << " | "
        << f3(mean(o.maxEdits, true)) << " / " << f3(mean(o.maxEdits, false)) << " | " << reach(0.6) << " | "
        << reach(0.5) << " | " << reach(0.25) << " |\n";
    }
  return s.str();
}

void writeCorrectingReport(const fs::path& folder, const std::vector<CorrectingRun>& runs,
                           const CorrectingUserOptions& o) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder)) throw OutputError(folder.string() + ": cannot create the directory");
  writeFileAtomically(
      folder / "correcting_user.csv",
      [&](std::ostream& out) {
        out << "tree,condition,pattern,leaf,edit,action,nodes,backward_rms_pct,forward_rms_pct,edit_ms\n";
        out.precision(9);
        for (const auto& r : runs)
          for (const auto& s : r.steps)
            out << r.tree << "," << r.condition << "," << r.pattern << "," << r.leaf << "," << s.edit << ",\""
                << s.action << "\"," << s.nodes << "," << s.backwardRms << "," << s.forwardRms << "," << s.ms << "\n";
      },
      false);
  writeFileAtomically(
      folder / "correcting_user.md", [&](std::ostream& out) { out << correctingMarkdown(runs, o); }, false);
  for (const char* leaf : {"leaf-on", "leaf-off"}) {
    LineChart c;
    c.title = std::string("Simulated correcting user, ") + leaf + ": RMS after each edit (mean over trees)";
    c.xLabel = "edits";
    c.yLabel = "RMS, % of bbox diagonal";
    int colour = 0;
    for (const char* pattern : {"sphere", "tls"}) {
      std::vector<const CorrectingRun*> sel;
      for (const auto& r : runs)
        if (r.leaf == leaf && r.pattern == pattern) sel.push_back(&r);
      if (sel.empty()) continue;
      for (bool backward : {true, false}) {
        std::vector<double> xs, ys;
        for (int e = 0; e <= o.maxEdits; ++e) {
          double sum = 0;
          for (const auto* r : sel) sum += backward ? after(*r, e).backwardRms : after(*r, e).forwardRms;
          xs.push_back(e);
          ys.push_back(sum / sel.size());
        }
        c.series.push_back(std::string(pattern) + (backward ? " backward" : " forward"));
        c.xs.push_back(xs);
        c.ys.push_back(ys);
        c.styles.push_back(SeriesStyle{colour, true, !backward, false});
      }
      ++colour;
    }
    if (c.series.empty()) continue;
    writeSvg(folder / (std::string("correcting_user_") + leaf + ".svg"), renderSvg(c));
  }
}

}  // namespace treesketch::eval
