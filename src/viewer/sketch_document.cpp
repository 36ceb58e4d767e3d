// SketchDocument: a sketch tied to its cloud. See include/treesketch/viewer/sketch_document.h.
#include "treesketch/viewer/sketch_document.h"

#include <chrono>
#include <ctime>
#include <system_error>

#include "treesketch/util/error.h"

namespace treesketch::viewer {

namespace fs = std::filesystem;

bool sameFile(const fs::path& a, const fs::path& b) {
  if (a.empty() || b.empty()) return false;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return fs::absolute(a, ec).lexically_normal() == fs::absolute(b, ec).lexically_normal();
}

fs::path SketchDocument::sketchPathFor(const fs::path& cloudPath) {
  if (cloudPath.empty()) return {};
  return cloudPath.parent_path() / (cloudPath.filename().string() + ".sketch.json");
}

fs::path SketchDocument::autosavePathFor(const fs::path& cloudPath) {
  if (cloudPath.empty()) return {};
  return cloudPath.parent_path() / (cloudPath.filename().string() + ".autosave.sketch.json");
}

void SketchDocument::setCloud(const fs::path& cloudPath, const geom::PointCloud& cloud) {
  cloudPath_ = cloudPath;
  cloud_ = io::makeCloudRecord(cloud, cloudPath, sketchPathFor(cloudPath));
  sketchPath_ = sketchPathFor(cloudPath);
  autosavePath_ = autosavePathFor(cloudPath);
  ownFile_.clear();
  failedLoads_.clear();
  endRecovery();
}

void SketchDocument::setAutosavePath(const fs::path& path) {
  if (std::string why = protectedReason(path); !why.empty())
    throw OptionsError("autosave: " + path.string() + " " + why + "; autosave stays at " +
                       (autosavePath_.empty() ? std::string("nothing (off)") : autosavePath_.string()));
  autosavePath_ = path;
}

std::string SketchDocument::protectedReason(const fs::path& path) const {
  if (sameFile(path, cloudPath_)) return "is the open cloud";
  for (const fs::path& failed : failedLoads_)
    if (sameFile(path, failed)) return "failed to load as a sketch (its contents would be lost)";
  return {};
}

void SketchDocument::noteFailedLoad(const fs::path& path) {
  if (protectedReason(path).empty()) failedLoads_.push_back(path);
  if (sameFile(ownFile_, path)) ownFile_.clear();
}

namespace {

std::string describeRecord(const io::SketchCloudRecord& r) {
  return (r.path.empty() ? std::string("a cloud") : r.path) + " (" + std::to_string(r.points) + " points)";
}

}  // namespace

std::string SketchDocument::loadQuestion(const fs::path& file, const std::optional<io::SketchCloudRecord>& record) const {
  if (!record || record->sameCloud(cloud_)) return {};
  return file.filename().string() + " was made for " + describeRecord(*record) + ", not for the open cloud " +
         (cloudPath_.empty() ? std::string("") : cloudPath_.filename().string() + " ") + "(" +
         std::to_string(cloud_.points) + " points). Load it onto this cloud anyway? (undoable)";
}

std::string SketchDocument::overwriteQuestion(const fs::path& path) const {
  std::error_code ec;
  if (!fs::exists(path, ec) || sameFile(path, ownFile_)) return {};
  try {
    io::SketchFile other = io::readSketchFile(path);
    if (other.cloud && other.cloud->sameCloud(cloud_)) return {};
    return path.string() + " holds a sketch of " + std::to_string(other.sketch.size()) + " nodes made for " +
           (other.cloud ? describeRecord(*other.cloud) : std::string("an unnamed cloud")) + ". Replace it?";
  } catch (const std::exception&) {
    return path.string() + " exists and is not a sketch of this cloud. Replace it?";
  }
}

void SketchDocument::save(const fs::path& path, const sketch::Sketch& sketch) {
  if (std::string why = protectedReason(path); !why.empty())
    throw OptionsError(path.string() + " " + why + ": not overwritten (save under another name)");
  io::SketchCloudRecord record = cloud_;
  record.path = io::makeCloudRecord(geom::PointCloud{}, cloudPath_, path).path;
  io::writeSketch(path, sketch, record);
  ownFile_ = path;
}

void SketchDocument::writeAutosave(const sketch::Sketch& sketch) {
  if (autosavePath_.empty()) return;
  if (sketch.empty()) {
    removeAutosave();
    return;
  }
  if (std::string why = protectedReason(autosavePath_); !why.empty())
    throw OptionsError(autosavePath_.string() + " " + why + ": not overwritten");
  io::SketchCloudRecord record = cloud_;
  record.path = io::makeCloudRecord(geom::PointCloud{}, cloudPath_, autosavePath_).path;
  io::writeSketch(autosavePath_, sketch, record);
}

bool SketchDocument::removeAutosave() {
  if (autosavePath_.empty() || !protectedReason(autosavePath_).empty()) return false;
  std::error_code ec;
  return fs::remove(autosavePath_, ec);
}

namespace {

/// "<autosave stem>.kept-YYYYmmdd-HHMMSS.sketch.json" beside `autosave`, not yet existing.
fs::path keptName(const fs::path& autosave) {
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&now, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
  std::string base = autosave.filename().string();
  const std::string suffix = ".sketch.json";
  if (base.size() > suffix.size() && base.compare(base.size() - suffix.size(), suffix.size(), suffix) == 0)
    base.resize(base.size() - suffix.size());
  fs::path p = autosave.parent_path() / (base + ".kept-" + stamp + suffix);
  for (int i = 2; fs::exists(p); ++i)
    p = autosave.parent_path() / (base + ".kept-" + stamp + "-" + std::to_string(i) + suffix);
  return p;
}

}  // namespace

fs::path SketchDocument::keepAutosave() {
  fs::path kept = keptName(autosavePath_);
  fs::rename(autosavePath_, kept);
  return kept;
}

std::string SketchDocument::findRecovery(bool& readable) {
  endRecovery();
  readable = true;
  std::error_code ec;
  if (autosavePath_.empty() || !fs::is_regular_file(autosavePath_, ec)) return {};
  try {
    io::SketchFile found = io::readSketchFile(autosavePath_);
    if (found.cloud && !found.cloud->sameCloud(cloud_)) {
      // Work for another cloud (the file at this path was replaced, or the autosave was named by
      // hand): not offered here, and kept aside so that this cloud's autosave does not replace it.
      const fs::path kept = keepAutosave();
      return "an autosave made for " + describeRecord(*found.cloud) + ", not for this cloud, was kept as " +
             kept.string() + " (load it with Load sketch onto its own cloud)";
    }
    recoveryPending_ = true;
    recoveryNodes_ = found.sketch.size();
    return "found unsaved work from an earlier session: " + autosavePath_.string() + " (" +
           std::to_string(recoveryNodes_) + " nodes): restore, discard or keep it";
  } catch (const std::exception& e) {
    recoveryPending_ = true;
    readable = false;
    recoveryError_ = e.what();
    return "the earlier session's autosave cannot be read: " + recoveryError_ + " (discard it or keep it)";
  }
}

void SketchDocument::endRecovery() {
  recoveryPending_ = false;
  recoveryNodes_ = 0;
  recoveryError_.clear();
}

}  // namespace treesketch::viewer
