// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// MJCF helpers shared by the scene composition (scene.cc) and the vehicle adapter
// (vehicle_adapter.cc), private to scene/.
#ifndef MJFORMATION_SCENE_SRC_MJCF_UTIL_HPP_
#define MJFORMATION_SCENE_SRC_MJCF_UTIL_HPP_

#include <string>

namespace mjf::runner::mjcf {

// The MJCF attributes that name another element of the model: a body, geom, joint, site,
// tendon or actuator (transmissions, sensors' objname/refname, contact pairs and excludes,
// equalities, slider-crank sites, `jointinparent` of actuators, `target` of cameras and
// lights). Composition prefixes them per copy; the adapter drops what refers outside the
// vehicle. Class, material, mesh, texture and hfield names are shared by all copies.
inline const char* const kReferenceAttributes[] = {
    "body",       "body1",         "body2",  "geom",     "geom1",   "geom2",   "joint",
    "joint1",     "joint2",        "site",   "site1",    "site2",   "refsite", "cranksite",
    "slidersite", "jointinparent", "tendon", "actuator", "objname", "refname", "target"};

// The folder of the model file `path` as an absolute path, so that text written elsewhere (the
// composed scene.xml in a run directory) still finds the model's asset files.
std::string ModelDirectory(const std::string& path);

}  // namespace mjf::runner::mjcf

#endif  // MJFORMATION_SCENE_SRC_MJCF_UTIL_HPP_
