// ViewerState's files: saving and loading the sketch through its SketchDocument (the cloud's
// record, the questions before loading another cloud's sketch or replacing another file, the
// files never written) and exporting the model's outputs. See viewer_state.h for the map of the
// files that implement ViewerState.
#include <memory>

#include "treesketch/io/sketch_file.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

bool ViewerState::saveSketch(const std::filesystem::path& path, bool replaceConfirmed) {
  if (sketch_.empty()) {
    error("save sketch: the sketch is empty: nothing to save");
    return false;
  }
  if (std::string why = doc_.protectedReason(path); !why.empty()) {
    error("save sketch: " + path.string() + " " + why + ": not overwritten (save under another name)");
    return false;
  }
  std::string question;
  if (!replaceConfirmed && !runAction("save sketch", [&] { question = doc_.overwriteQuestion(path); })) return false;
  if (!question.empty()) return ask(question, [this, path] { return writeSketchFile(path); });
  return writeSketchFile(path);
}

bool ViewerState::writeSketchFile(const std::filesystem::path& path) {
  return runAction("save sketch", [&] {
    doc_.save(path, sketch_);
    dirty_ = false;
    // The work is in its file now: the autosave has nothing more to bring back.
    if (!doc_.recoveryPending()) doc_.removeAutosave();
    info("saved sketch to " + path.string() + " (" + std::to_string(sketch_.size()) + " nodes)");
  });
}

bool ViewerState::loadSketch(const std::filesystem::path& path) {
  io::SketchFile file;
  if (!runAction("load sketch", [&] { file = io::readSketchFile(path); })) {
    doc_.noteFailedLoad(path);  // never written afterwards: its contents are not ours to replace
    return false;
  }
  const std::string question = doc_.loadQuestion(path, file.cloud);
  if (question.empty()) return takeLoadedSketch(path, std::move(file.sketch), true);
  auto loaded = std::make_shared<sketch::Sketch>(std::move(file.sketch));
  return ask(question, [this, path, loaded] { return takeLoadedSketch(path, std::move(*loaded), false); });
}

bool ViewerState::takeLoadedSketch(const std::filesystem::path& path, sketch::Sketch loaded, bool ownCloud) {
  bool ok = edit("load sketch", "load sketch " + path.filename().string(), "", [&] {
    sketch_ = std::move(loaded);
    tools_.selected_ = kNoNode;
    tools_.active_ = kNoNode;
  });
  if (!ok) return false;
  tools_.activeChosen_ = false;
  // A sketch made for this cloud is this document's file; another cloud's stays untouched (a
  // save goes to this cloud's own sketch path, and replacing that other file asks first).
  if (ownCloud) doc_.noteLoaded(path), dirty_ = false;
  info("loaded sketch " + path.string() + " (" + std::to_string(sketch_.size()) + " nodes)" +
       (ownCloud ? "" : "; it was made for another cloud: Save writes this cloud's own sketch file"));
  return true;
}

bool ViewerState::exportMesh(const std::filesystem::path& path) { return exportModel(ModelFile::Mesh, path); }

bool ViewerState::exportModel(ModelFile what, const std::filesystem::path& path, double unitMetres) {
  static constexpr const char* kNames[] = {"mesh", "cylinder table", "TreeQSM table", "metrics", "report"};
  const char* name = kNames[static_cast<int>(what)];
  return runAction(std::string("export ") + name, [&] {
    if (!recon_) throw OptionsError("no cloud is open");
    if (what == ModelFile::Mesh ? recon_->mesh().empty() : false)
      throw OptionsError("no mesh to export: no node has been fitted yet");
    const model::TreeModel tree = scene_.treeModel();
    if (what != ModelFile::Mesh && tree.empty())
      throw OptionsError(std::string("no ") + name + " to export: no two linked nodes are fitted yet");
    model::OutputPaths out;
    std::string* target[] = {&out.mesh, &out.cylinders, &out.qsm, &out.metrics, &out.report};
    *target[static_cast<int>(what)] = path.string();
    if (std::string why = doc_.protectedReason(path); !why.empty())
      throw OptionsError(path.string() + " " + why + ": not overwritten");
    model::checkOutputs(out, {doc_.cloudPath().string()});
    model::MeasureOptions mo;
    mo.unitMetres = unitMetres;
    mo.fit = what == ModelFile::Report;
    const bool measured = what == ModelFile::Metrics || what == ModelFile::Report;
    const model::ModelMeasures m = measured ? model::measure(tree, cloud_, mo) : model::ModelMeasures{};
    nlohmann::json header;
    header["cloud"] = doc_.cloudPath().string();
    header["sketch"] = doc_.sketchPath().string();
    header["nodes"] = sketch_.size();
    model::writeOutputs(tree, m, out, header);
    info("exported " + std::string(name) + " to " + path.string() +
         (what == ModelFile::Mesh ? " (" + std::to_string(tree.mesh.triangles.size()) + " triangles)"
                                  : " (" + std::to_string(tree.cylinders.size()) + " cylinders)"));
  });
}

}  // namespace treesketch::viewer
