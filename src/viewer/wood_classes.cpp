// ViewerState's wood/leaf classification: the classification as a background job, the classes
// after the lassos (what the fits, the strokes and the colouring use), the wood lasso, and the
// automatic skeleton on the wood only (as `reconstruct --auto --wood-only`). See viewer_state.h
// for the map of the files that implement ViewerState.
//
// Threading: the jobs read only the open cloud (setCloud is refused while a job runs) and their
// own copies; the classification is taken in on the window's thread (takeJobOutcome).
#include <memory>

#include "treesketch/edit/correction_tools.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

namespace {

/// Fewer wood points than this is no tree's wood (as `reconstruct --auto --wood-only`).
constexpr std::size_t kMinWoodPoints = 100;

/// The lassos with their cameras: what the classes after the lassos depend on.
std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>> lassosOf(const sketch::Sketch& sk) {
  std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>> out;
  for (const sketch::NotWoodLasso& l : sk.notWood()) out.emplace_back(l, sk.cameras()[l.camera]);
  return out;
}

bool sameLassos(const std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>>& a,
                const std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i].first == b[i].first) || !(a[i].second.view == b[i].second.view) ||
        !(a[i].second.projection == b[i].second.projection))
      return false;
  return true;
}

}  // namespace

std::vector<std::uint8_t> ViewerState::leafFlags() const {
  std::vector<std::uint8_t> leaf;
  if (!classes_) return leaf;
  leaf.reserve(classes_->wood.size());
  for (std::uint8_t w : classes_->wood) leaf.push_back(w ? 0 : 1);
  return leaf;
}

void ViewerState::applyLeafPoints() {
  if (!recon_) return;
  runAction("classification", [&] { recon_->setLeafPoints(leafFlags()); });
}

void ViewerState::takeClassification(std::shared_ptr<const classify::Classification> classes) {
  if (!classes || classes->wood.size() != cloud_.size()) {
    error("wood/leaf classification: the result does not match the open cloud; not taken");
    return;
  }
  classes_ = std::move(classes);
  ++classesVersion_;
  applyLeafPoints();
  rebuild();  // every node that is not a kept circle is fitted again, on the wood
  scene_.colorsStale_ = true;
  const std::size_t n = woodPointCount();
  char share[32];
  std::snprintf(share, sizeof share, "%.1f %%", 100.0 * double(n) / double(std::max<std::size_t>(cloud_.size(), 1)));
  info("wood/leaf classification: " + std::to_string(n) + " of " + std::to_string(cloud_.size()) +
       " points are wood (" + share +
       "); the fits and strokes now use the wood only (lassos correct it: X not wood, "
       "Shift+X wood)");
}

const std::vector<std::uint8_t>& ViewerState::woodAfterLassos() const {
  if (!classes_) {
    woodAfterLassos_.clear();
    woodCount_ = 0;
    return woodAfterLassos_;
  }
  std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>> lassos = lassosOf(sketch_);
  if (woodFor_ == classesVersion_ && woodAfterLassos_.size() == cloud_.size() && sameLassos(lassos, woodLassos_))
    return woodAfterLassos_;
  const std::vector<std::uint8_t> leaf = leafFlags();
  woodAfterLassos_.assign(cloud_.size(), 0);
  woodCount_ = 0;
  for (std::size_t i = 0; i < cloud_.size(); ++i) {
    woodAfterLassos_[i] = edit::isWoodPoint(sketch_, leaf, i, cloud_.positions[i]) ? 1 : 0;
    woodCount_ += woodAfterLassos_[i];
  }
  woodFor_ = classesVersion_;
  woodLassos_ = std::move(lassos);
  return woodAfterLassos_;
}

std::size_t ViewerState::woodPointCount() const {
  woodAfterLassos();
  return woodCount_;
}

bool ViewerState::startClassifyJob() {
  if (refuseWhileBusy("wood/leaf classification")) return false;
  if (cloud_.empty()) {
    error("wood/leaf classification: open a point cloud first");
    return false;
  }
  std::optional<geom::UpAxis> axis = libraryUpAxis(view_.up_);
  if (!axis) {
    error(std::string("wood/leaf classification: needs up +y or +z (the view's up is ") + toString(view_.up_) + ")");
    return false;
  }
  const geom::PointCloud* cloud = &cloud_;  // setCloud is refused while a job runs
  const geom::UpAxis up = *axis;
  jobs_.start(
      "wood/leaf classification",
      [cloud, up](const ProgressFn& progress) {
        if (progress) progress(0, 1);  // a cancel before the work starts stops it here
        JobResult out;
        out.classes = std::make_shared<const classify::Classification>(classify::classifyWood(*cloud, up));
        return out;
      },
      JobSteps::Classify);
  info("wood/leaf classification: running");
  return true;
}

bool ViewerState::startWoodSkeletonJob() {
  if (refuseWhileBusy("automatic skeleton on the wood")) return false;
  if (cloud_.empty()) {
    error("automatic skeleton on the wood: open a point cloud first");
    return false;
  }
  std::optional<geom::UpAxis> axis = libraryUpAxis(view_.up_);
  if (!axis) {
    error(std::string("automatic skeleton on the wood: needs up +y or +z (the view's up is ") + toString(view_.up_) +
          ")");
    return false;
  }
  // The wood is modelled with the leaf-off preset: what is left is meant to be wood.
  const skeleton::AutoSkeletonOptions options = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, *axis);
  const geom::PointCloud* cloud = &cloud_;
  const geom::UpAxis up = *axis;
  std::shared_ptr<const classify::Classification> known = classes_;
  const sketch::Sketch lassos = sketch_;  // only its lassos are read
  jobs_.start(
      "automatic skeleton on the wood",
      [options, cloud, up, known, lassos](const ProgressFn& progress) {
        JobResult out;
        std::shared_ptr<const classify::Classification> classes = known;
        if (!classes) {
          classes = std::make_shared<const classify::Classification>(classify::classifyWood(*cloud, up));
          out.classes = classes;
        }
        std::vector<std::uint8_t> leaf(classes->wood.size());
        for (std::size_t i = 0; i < leaf.size(); ++i) leaf[i] = classes->wood[i] ? 0 : 1;
        const geom::PointCloud wood = edit::woodOnly(*cloud, lassos, leaf);
        if (wood.size() < kMinWoodPoints)
          throw DegenerateInputError(std::to_string(wood.size()) + " of " + std::to_string(cloud->size()) +
                                     " points are wood, too few to model (lasso the wood, or use Auto skeleton)");
        skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(wood, options, progress);
        if (r.sketch.empty()) throw OptionsError("no skeleton found in the wood points");
        out.sketch = std::move(r.sketch);
        return out;
      },
      known ? JobSteps::Skeleton : JobSteps::ClassifyThenSkeleton);
  info("automatic skeleton on the wood: running (Cancel stops it; the sketch stays as it is until it is done)");
  return true;
}

bool ViewerState::requestAutoSketchSkeletonWood() {
  return askBeforeReplacing("Replace the sketch (" + std::to_string(sketch_.size()) +
                                " nodes, with hand edits) by the automatic skeleton on the wood? (undoable)",
                            [this] { return startWoodSkeletonJob(); });
}

bool ViewerState::lassoWood(const std::vector<geom::Vec2>& polygon) {
  if (cloud_.empty()) {
    error("wood lasso: open a point cloud first");
    return false;
  }
  std::size_t marked = 0;
  bool ok = edit("wood lasso", "wood lasso", "",
                 [&] { marked = edit::lassoWood(sketch_, cloud_, view_.orbit_.camera(), polygon); });
  if (ok) {
    scene_.colorsStale_ = true;
    info("wood lasso: " + std::to_string(marked) + " points marked wood" +
         (classes_
              ? std::string(" (the fits use them whatever the classification said)")
              : std::string(" (they override not-wood lassos drawn before; classify the cloud, K, for the rest)")));
  }
  return ok;
}

}  // namespace treesketch::viewer
