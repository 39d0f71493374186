// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The names an instance's vehicles carry in the model it was compiled into. A scene attached
// into another (MuJoCo's mjs_attach, Python's MjSpec.attach) has every element renamed
// `prefix + name + suffix`, the instance too; the instance's configuration keeps the names as
// written. MuJoCo carries an instance through an attach only when an element of the attached
// tree references it, so each vehicle's body references the instance that flies it
// (`<body name="uav0_vehicle"><plugin instance="swarm"/>`), and those bodies tell the affixes:
// each attached copy finds its own, whatever the other copies are called.
#ifndef MJFORMATION_MUJOCO_PLUGIN_ATTACH_NAMES_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_ATTACH_NAMES_HPP_

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::native {

// The affixes of instance `instance`, read from the bodies that reference it (body_plugin):
// the one (prefix, suffix) under which every name of `bodies` (the vehicles' bodies as the
// configuration names them) is a body referencing the instance, and no other body references
// it. An instance that no body references (declared in <extension> alone) reads the names as
// written. Anything else (a vehicle attached without the others, two copies' bodies on one
// instance) throws std::runtime_error naming `where` and the bodies. Valid while the model
// compiles (MuJoCo's nstate): names and body_plugin are set by then.
runner::SceneNames InstanceNames(const mjModel* m, int instance,
                                 const std::vector<std::string>& bodies, const std::string& where);

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_ATTACH_NAMES_HPP_
