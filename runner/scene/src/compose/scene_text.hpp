// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The composed scene's MJCF text (scene.cc), private to scene/. A scene composed in blocks
// (scene_blocks.hpp) holds, besides the vehicles, what the blocks left: frames that only group
// the vehicles' frames and default classes that only group the vehicles' classes. Neither
// reaches the compiled model; without them MuJoCo's text is the one a scene composed by one
// attach per vehicle gives.
#ifndef MJFORMATION_SCENE_SRC_SCENE_TEXT_HPP_
#define MJFORMATION_SCENE_SRC_SCENE_TEXT_HPP_

#include <optional>
#include <string>

namespace mjf::runner {

// `written`: MuJoCo's text of a scene composed in blocks. Returns it without the frames that
// have no attributes and hold only frames, and without the default classes whose names contain
// `marker` (the blocks' own), their children in their place, as MuJoCo's writer prints it.
// Nothing when a block's class holds settings (its children would change) or the text does
// not read.
std::optional<std::string> WithoutBlocks(const std::string& written, const char* marker);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_SCENE_TEXT_HPP_
