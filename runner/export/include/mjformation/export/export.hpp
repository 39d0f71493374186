// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation export`: an experiment as a self-contained MuJoCo scene whose controllers are
// declared as native engine plugins (libmjformation_mujoco.so, docs/PLUGINS.md).
#ifndef MJFORMATION_EXPORT_EXPORT_HPP_
#define MJFORMATION_EXPORT_EXPORT_HPP_

#include <stdexcept>
#include <string>
#include <vector>

namespace mjf::runner {

class ExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExportResult {
  std::string scene_path;          // DIR/scene.xml
  std::vector<std::string> notes;  // what was not carried because it does not shape the flight
};

// How to read the experiment file, as for `mjformation run`.
struct ExportOptions {
  std::vector<std::string> overrides;    // "section.key=value" (--set)
  std::vector<std::string> plugin_path;  // extra plugin folders (--plugin-path), carried
  bool overwrite = false;                // write into an existing non-empty folder
};

// Writes DIR/scene.xml for the experiment file, and beside it a copy of every file the scene
// names (the vehicle and scene models with their asset files, the data files), named relative
// to the scene, so DIR can be moved (docs/PLUGINS.md, "Scenes that travel"). Refuses, naming
// the file and the key, whatever the native path cannot carry (see the list in export.cc), and
// refuses a DIR that is a file, and an existing non-empty DIR unless `options.overwrite`, which
// replaces scene.xml and the files export wrote there (its manifest, mjformation_export.txt,
// says which), never another: a file export would replace that it did not write is refused,
// naming it, before anything is written. Throws ExportError or ConfigError.
ExportResult ExportExperiment(const std::string& experiment, const std::string& out_dir,
                              const ExportOptions& options = {});

// The scene text alone, every path absolute (ExportExperiment's scene names the copies beside it
// by relative paths instead), for the tests and scenes compiled from memory.
std::string ExportedSceneXml(const std::string& experiment, const ExportOptions& options,
                             std::vector<std::string>* notes);

}  // namespace mjf::runner

#endif  // MJFORMATION_EXPORT_EXPORT_HPP_
