// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// MJCF helpers shared by the scene composition (scene.cc) and the vehicle adapter's steps
// (vehicle_*.cc, actuator_mapping.cc), private to scene/.
#ifndef MJFORMATION_SCENE_SRC_MJCF_UTIL_HPP_
#define MJFORMATION_SCENE_SRC_MJCF_UTIL_HPP_

#include <tinyxml2.h>

#include <set>
#include <string>

namespace mjf::runner::mjcf {

// The MJCF attributes that name another element of the model, each with the kind of element it
// names: transmissions, sensors' objname/refname (kind given by objtype/reftype, "object" here),
// contact pairs and excludes, equalities, slider-crank sites, `jointinparent` of actuators,
// `target` of cameras and lights. Composition prefixes them all per copy; the adapter drops what
// refers outside the vehicle and renames by kind. Class, material, mesh, texture and hfield names
// are shared by all copies. One list, so that prefixing, dropping and renaming agree.
struct ReferenceAttribute {
  const char* name;  // the attribute
  const char* kind;  // the element tag it names ("object": see objtype/reftype)
};
inline const ReferenceAttribute kReferenceAttributes[] = {
    {"body", "body"},           {"body1", "body"},     {"body2", "body"},
    {"geom", "geom"},           {"geom1", "geom"},     {"geom2", "geom"},
    {"joint", "joint"},         {"joint1", "joint"},   {"joint2", "joint"},
    {"site", "site"},           {"site1", "site"},     {"site2", "site"},
    {"refsite", "site"},        {"cranksite", "site"}, {"slidersite", "site"},
    {"jointinparent", "joint"}, {"tendon", "tendon"},  {"actuator", "actuator"},
    {"objname", "object"},      {"refname", "object"}, {"target", "body"}};

// The folder of the model file `path` as an absolute path, so that text written elsewhere (the
// composed scene.xml in a run directory) still finds the model's asset files.
std::string ModelDirectory(const std::string& path);

// Whether `path` is a regular file.
bool IsFile(const std::string& path);

// "dir/rel" unless rel is absolute (MuJoCo's rule for model-relative folders and files).
std::string Join(const std::string& dir, const std::string& rel);

// "file:line" of element `e` of the model file `path`, for messages.
std::string At(const std::string& path, const tinyxml2::XMLElement* e);

// "<tag name=\"...\">" for messages.
std::string Describe(const tinyxml2::XMLElement* e);

// Whether `e` or an element below it is a <tag name="name">.
bool HasNamed(const tinyxml2::XMLElement* e, const char* tag, const std::string& name);

// Adds the name of `e` and of every element below it to `names`.
void CollectNames(const tinyxml2::XMLElement* e, std::set<std::string>* names);

// The text of an attribute that may be absent ("" then).
inline std::string Str(const char* s) { return s ? s : ""; }

}  // namespace mjf::runner::mjcf

#endif  // MJFORMATION_SCENE_SRC_MJCF_UTIL_HPP_
