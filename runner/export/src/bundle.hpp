// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The files an exported scene needs, copied into its folder and named relative to it, so that
// the folder can be moved or handed on (docs/PLUGINS.md, "Scenes that travel"). Private to
// export: export.cc decides what is carried, this file where the carried files go.
#ifndef MJFORMATION_EXPORT_SRC_BUNDLE_HPP_
#define MJFORMATION_EXPORT_SRC_BUNDLE_HPP_

#include <toml++/toml.h>

#include <map>
#include <string>
#include <vector>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

// Layout of OUT_DIR: scene.xml, the anchor (scene_anchor.hpp), vehicle/ (the [vehicles] model
// and the asset files it names, below it as below the original), world/ (the [vehicles] scene
// model, likewise), assets/ (the asset files the composed scene names), data/ (a plugin's `file`
// and [formation.shape] file) and the manifest kManifest, the list of what export wrote.
class SceneBundle {
 public:
  static constexpr char kManifest[] = "mjformation_export.txt";

  explicit SceneBundle(std::string out_dir);

  // Rewrites the resolved (absolute) paths of the experiment document `doc` ([vehicles] model
  // and scene, a plugin's `file`, [formation.shape] file) into paths relative to the scene's
  // folder, and records the files to copy. [run] plugin_path names the user's folders of
  // libraries: made absolute, not copied, and a note says so.
  void Relocate(toml::table& doc, const ExperimentConfig& config, std::vector<std::string>* notes);

  // The composed scene `xml` with its asset files copied and named relative to the scene, and
  // the anchor texture declared.
  std::string Relocated(std::string xml);

  // Writes scene.xml and the recorded files. A file already there is replaced only if export
  // wrote it (it is in the manifest) or it holds the same bytes; any other is refused, naming
  // it. Throws ExportError.
  void Write(const std::string& scene_xml) const;

 private:
  // Records `source` to be copied to `relative` (under OUT_DIR); returns the relative name it
  // gets (another source of the same name gets a numbered one).
  std::string Add(const std::string& source, const std::string& relative);
  // The model file and the asset files it names, under `folder`; returns the model's new name.
  std::string AddModel(const std::string& model_path, const std::string& folder);

  std::string out_dir_;
  std::map<std::string, std::string> copies_;  // relative destination -> source
};

}  // namespace mjf::runner

#endif  // MJFORMATION_EXPORT_SRC_BUNDLE_HPP_
