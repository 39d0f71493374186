// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What one vehicle's model must not bring into a scene shared by many copies of it
// (vehicle_adapter.cc's scoping steps), private to scene/. Each step edits the document in
// place and appends one note per change to `notes`.
#ifndef MJFORMATION_SCENE_SRC_VEHICLE_SCOPING_HPP_
#define MJFORMATION_SCENE_SRC_VEHICLE_SCOPING_HPP_

#include <tinyxml2.h>

#include <string>
#include <vector>

namespace mjf::runner {

using Notes = std::vector<std::string>;

// The model's top-level defaults would apply to the whole shared scene (the floor too, through
// scene.cc's merge): they move into a class of their own, which the vehicle's elements use.
void ScopeDefaults(tinyxml2::XMLDocument* doc, tinyxml2::XMLElement* root,
                   tinyxml2::XMLElement* body, Notes* notes);

// Memory sizes written for one vehicle would be too small for a swarm of them: MuJoCo sizes
// the composed scene itself.
void ScopeSizes(tinyxml2::XMLElement* root, Notes* notes);

// Everything in <worldbody> but the vehicle `body`: floors, lights, cameras, other bodies; and
// the vehicle's own lights (N copies of a light would relight the shared scene).
void DropWorldExtras(tinyxml2::XMLElement* body, Notes* notes);

// The model's <option> as the composed scene will have it, one note per value that changes or
// matters: its timestep and integrator are replaced by the experiment's (scene.cc), its gravity,
// density, viscosity and wind are kept for the whole scene (every vehicle is a copy of this
// model, so the fluid forces they imply act on all of them alike), its flags are kept.
void NoteModelOptions(const tinyxml2::XMLElement* root, Notes* notes);

// Sections scene.cc does not copy (keyframes, visual, statistic, extensions, ...).
void DropSections(tinyxml2::XMLElement* root, Notes* notes);

// Sensors, contact pairs, equalities, tendons and other actuators that name something dropped
// (a floor geom, a world site) would not compile: they go too.
void DropDanglingReferences(tinyxml2::XMLElement* root, const tinyxml2::XMLElement* body,
                            Notes* notes);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_SRC_VEHICLE_SCOPING_HPP_
