// The desktop tool's sketch as a document tied to its cloud: which cloud is open (its path, point
// count and content hash), where its sketch is saved by default ("tree.las" ->
// "tree.las.sketch.json") and autosaved ("tree.las.autosave.sketch.json"), which files must never
// be written (the open cloud, a file that failed to load as a sketch), and the questions to ask
// before a sketch made for another cloud is loaded or another file is replaced. Plain C++, no GL;
// ViewerState owns one and asks it before every load, save and autosave; it also holds the offer of
// an earlier session's autosave (crash recovery).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::viewer {

class SketchDocument {
 public:
  /// "tree.las" -> "tree.las.sketch.json" beside it: the whole file name, so that tree.las and
  /// tree.xyz in one folder keep their own sketches. Empty for an empty path.
  static std::filesystem::path sketchPathFor(const std::filesystem::path& cloudPath);
  /// "tree.las" -> "tree.las.autosave.sketch.json" beside it. Empty for an empty path.
  static std::filesystem::path autosavePathFor(const std::filesystem::path& cloudPath);

  /// A new cloud: records its path (empty: a cloud not read from a file, such as the demo tree),
  /// point count and content hash; the sketch and autosave paths follow the cloud's name (both
  /// empty for an empty path). Forgets the files loaded or saved for the previous cloud.
  void setCloud(const std::filesystem::path& cloudPath, const geom::PointCloud& cloud);
  const std::filesystem::path& cloudPath() const { return cloudPath_; }
  std::uint64_t cloudPoints() const { return cloud_.points; }
  const std::string& cloudHash() const { return cloud_.hash; }

  const std::filesystem::path& sketchPath() const { return sketchPath_; }
  void setSketchPath(const std::filesystem::path& path) { sketchPath_ = path; }
  const std::filesystem::path& autosavePath() const { return autosavePath_; }
  /// Throws OptionsError (and leaves the autosave path as it was) when `path` may not be written
  /// (protectedReason); empty turns autosave off.
  void setAutosavePath(const std::filesystem::path& path);

  /// Why `path` must never be written ("" when it may be): it is the open cloud, or a file that
  /// failed to load as a sketch (its contents are not a sketch this tool wrote; replacing it would
  /// lose whatever it holds). Compares files, not spellings (a relative and an absolute path to
  /// one file are the same file).
  std::string protectedReason(const std::filesystem::path& path) const;
  /// A file that failed to load as a sketch (never written afterwards).
  void noteFailedLoad(const std::filesystem::path& path);

  /// The question to ask before a sketch file whose cloud record is `record` replaces the sketch
  /// ("" when it was made for this cloud or does not say which cloud it was made for).
  std::string loadQuestion(const std::filesystem::path& file, const std::optional<io::SketchCloudRecord>& record) const;
  /// The question to ask before saving to `path` ("" when the file is not there, is the file this
  /// document last loaded or saved, or holds a sketch made for this cloud). Reads the file.
  std::string overwriteQuestion(const std::filesystem::path& path) const;

  /// Writes `sketch` with this cloud's record to `path` (atomically) and remembers the file as
  /// this document's. Throws OptionsError for a protected path, the writer's errors otherwise.
  void save(const std::filesystem::path& path, const sketch::Sketch& sketch);
  /// Remembers `path` as this document's file (after a load of a sketch made for this cloud).
  void noteLoaded(const std::filesystem::path& path) { ownFile_ = path; }

  /// Writes the autosave (nothing when autosave is off); an empty sketch removes it instead, as
  /// there is no work to bring back.
  void writeAutosave(const sketch::Sketch& sketch);
  /// Deletes the autosave file if there is one; true when a file was removed.
  bool removeAutosave();
  /// Renames the autosave file to "<autosave>.kept-<date>-<time>.sketch.json" beside it (a name
  /// not yet taken), loadable by hand; returns the new name. Throws std::filesystem's errors.
  std::filesystem::path keepAutosave();

  /// Crash recovery: an autosave found at autosavePath() is work from an earlier session (a crash,
  /// or a window closed with unsaved edits). findRecovery() looks for one and, when found, holds it
  /// as an offer (recoveryPending()) until endRecovery(): meanwhile the autosave is never written.
  /// Returns the status text to show ("" when there is nothing to offer); `readable` is false when
  /// the file cannot be read (recoveryError() says why). An autosave whose cloud record names
  /// another cloud (point count or hash differ) is not offered: it is renamed as keepAutosave()
  /// does, so that it is neither restored onto this cloud nor replaced by this cloud's autosave.
  std::string findRecovery(bool& readable);
  bool recoveryPending() const { return recoveryPending_; }
  /// Nodes in the waiting autosave (0 when it cannot be read; recoveryError() says why).
  std::size_t recoveryNodes() const { return recoveryNodes_; }
  const std::string& recoveryError() const { return recoveryError_; }
  /// The offer is answered (or withdrawn: another cloud is opened).
  void endRecovery();

 private:
  std::filesystem::path cloudPath_, sketchPath_, autosavePath_, ownFile_;
  io::SketchCloudRecord cloud_;
  std::vector<std::filesystem::path> failedLoads_;
  bool recoveryPending_ = false;
  std::size_t recoveryNodes_ = 0;
  std::string recoveryError_;
};

/// The same file: equivalent when both exist, else the same absolute, normalised path.
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace treesketch::viewer
