// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// An MJCF file read as MuJoCo reads it (vehicle_adapter.cc's first step), private to scene/.
#ifndef MJFORMATION_SCENE_SRC_MJCF_DOCUMENT_HPP_
#define MJFORMATION_SCENE_SRC_MJCF_DOCUMENT_HPP_

#include <tinyxml2.h>

#include <string>

namespace mjf::runner::mjcf {

// Reads the model file `path` into `doc`: its <include>s inlined (files relative to `dir`, the
// model's folder, as MuJoCo finds them) and each section that appears several times merged into
// its first copy. Returns the <mujoco> root. Throws SceneError naming `where` (the experiment
// key), the file and the line.
tinyxml2::XMLElement* ReadModelDocument(const std::string& path, const std::string& dir,
                                        const std::string& where, tinyxml2::XMLDocument* doc);

}  // namespace mjf::runner::mjcf

#endif  // MJFORMATION_SCENE_SRC_MJCF_DOCUMENT_HPP_
