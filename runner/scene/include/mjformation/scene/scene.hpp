// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Composes one scene from the world (mjcf/scene.xml) and 1 + N copies of a vehicle model
// (docs/ARCHITECTURE.md, "Vehicle model contract"), names prefixed uav<i>_, with MuJoCo's model
// editing API (mjSpec). The result is the compiled model and its MJCF text, written by MuJoCo:
// saved next to the results, the text loads in MuJoCo alone and compiles to the same model.
#ifndef MJFORMATION_SCENE_SCENE_HPP_
#define MJFORMATION_SCENE_SCENE_HPP_

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct mjModel_;

namespace mjf::runner {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SceneRequest {
  std::string scene_path;                        // the world
  std::string vehicle_path;                      // one vehicle
  std::vector<std::array<double, 3>> positions;  // initial position of vehicles 0..N, m
  // Index of the first vehicle (names uav<first_vehicle + i>_): a partition of the swarm
  // (partitioned_physics.hpp) holds a contiguous range of it.
  int first_vehicle = 0;
  double timestep = 0.001;     // s
  int offscreen_width = 1280;  // offscreen buffer, pixels
  int offscreen_height = 720;
  bool strip_actuators = false;   // wrench rotor model: rotors become body wrenches, no actuators
  bool disable_contacts = false;  // <option><flag contact="disable"/>: no collision detection
  // Bring your own quadrotor: the vehicle as adapted MJCF text (vehicle_adapter.hpp), used
  // instead of reading vehicle_path when not empty; the notes go into the scene's header.
  std::string vehicle_xml;
  std::vector<std::string> vehicle_notes;
  // false: the compiled model only, ComposedScene::xml left empty (MuJoCo's writer is about a
  // seventh of a large swarm's composition; a partition's text is never recorded).
  bool write_text = true;
};

struct ModelDeleter {
  void operator()(mjModel_* m) const;  // mj_deleteModel
};

struct ComposedScene {
  std::unique_ptr<mjModel_, ModelDeleter> model;  // compiled once, from the composed spec
  std::string xml;  // the same spec as MJCF (MuJoCo's writer), with a header comment
  // A contract-form vehicle (no vehicle_xml): what composition changed or kept of its <option>
  // (an adapted model's notes come from the adapter).
  std::vector<std::string> notes;
};

// Throws SceneError naming the file (and XML line) on bad input, and `name` (the scene's name in
// messages) with MuJoCo's message when the composed model does not compile.
ComposedScene ComposeScene(const SceneRequest& request, const std::string& name);

// Compiles MJCF text held in memory (no temporary file). Throws SceneError with MuJoCo's
// message, prefixed with `name`.
mjModel_* CompileModel(const std::string& xml, const std::string& name);

// Prefix of vehicle i's names in a composed scene.
std::string VehiclePrefix(int vehicle);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SCENE_HPP_
