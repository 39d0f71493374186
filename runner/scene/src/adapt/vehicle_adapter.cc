// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The adapter is a pipeline of steps of one job each: read the MJCF (mjcf_document), keep out
// of the shared scene what one vehicle must not bring (vehicle_scoping), rename the body and
// the contract's names (vehicle_renaming), map the actuators (actuator_mapping), resolve the
// assets (vehicle_assets), add the contract's site and sensors (vehicle_sensors, through mjSpec).
#include "mjformation/scene/vehicle_adapter.hpp"

#include <tinyxml2.h>

#include <cstring>

#include "adapt/actuator_mapping.hpp"
#include "adapt/mjcf_document.hpp"
#include "adapt/vehicle_assets.hpp"
#include "adapt/vehicle_renaming.hpp"
#include "adapt/vehicle_scoping.hpp"
#include "adapt/vehicle_sensors.hpp"
#include "mjcf_util.hpp"
#include "mjformation/config/source_location.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using tinyxml2::XMLElement;

bool HasFreeJoint(const XMLElement* b) {
  bool free = false;
  for (const XMLElement* c = b->FirstChildElement(); c; c = c->NextSiblingElement()) {
    free |= std::strcmp(c->Name(), "freejoint") == 0 ||
            (std::strcmp(c->Name(), "joint") == 0 && c->Attribute("type", "free"));
  }
  return free;
}

// The mapped body: a top-level body of <worldbody> with a free joint.
XMLElement* FindVehicleBody(XMLElement* root, const VehicleMapping& m) {
  XMLElement* world = root->FirstChildElement("worldbody");
  std::string top;
  for (XMLElement* b = world ? world->FirstChildElement("body") : nullptr; b;
       b = b->NextSiblingElement("body")) {
    const char* n = b->Attribute("name");
    if (n && m.body == n) {
      if (!HasFreeJoint(b)) {
        throw SceneError(m.body_where + ": " + mjcf::At(m.model_path, b) + ": body '" + m.body +
                         "' has no free joint (<freejoint/> or <joint type=\"free\"/>): a "
                         "vehicle must move freely in the world");
      }
      return b;
    }
    top += (top.empty() ? "'" : ", '") + std::string(n ? n : "(unnamed)") + "'";
  }
  throw SceneError(m.body_where + ": " + m.model_path + " has no top-level body named '" + m.body +
                   "' in <worldbody> (its top-level bodies: " + (top.empty() ? "none" : top) + ")");
}

}  // namespace

AdaptedVehicle AdaptVehicle(const VehicleMapping& m) {
  const std::string dir = mjcf::ModelDirectory(m.model_path);
  tinyxml2::XMLDocument doc;
  XMLElement* root = mjcf::ReadModelDocument(m.model_path, dir, m.body_where, &doc);
  XMLElement* body = FindVehicleBody(root, m);
  Notes notes;
  ScopeDefaults(&doc, root, body, &notes);
  ScopeSizes(root, &notes);
  NoteModelOptions(root, &notes);
  DropWorldExtras(body, &notes);
  DropSections(root, &notes);
  RenameVehicleBody(root, body, m.body, m.model_path, m.body_where, &notes);
  MapRotors(root, body, m, &notes);
  MakeRoomForContractNames(root, &notes);
  DropDanglingReferences(root, body, &notes);
  notes = ResolveAssets(root, body, m.model_path, dir, std::move(notes));
  // The contract's site and sensors go in through MuJoCo's model editing API, which also
  // writes the adapted text.
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  const std::string label = m.model_path + " (adapted to the vehicle contract)";
  AdaptedVehicle out;
  out.xml = std::string("<!-- ") + m.model_path + " adapted to the mjformation vehicle contract" +
            " (docs/VEHICLES.md) -->\n" + AddImuAndSensors(printer.CStr(), label, &notes);
  out.notes = notes;
  return out;
}

AdaptedVehicle AdaptConfiguredVehicle(const ExperimentConfig& config, const mjfPlugin& attitude) {
  if (config.vehicle_body.empty() && config.vehicle_rotors.empty()) return {};
  VehicleMapping m;
  m.model_path = config.model_path;
  m.body = config.vehicle_body.empty() ? "vehicle" : config.vehicle_body;
  for (int k = 0; k < attitude.n_actuators; ++k) m.actuator_names.push_back(attitude.actuators[k]);
  m.rotors = config.vehicle_rotors.empty() ? m.actuator_names : config.vehicle_rotors;
  auto where = [&](const ValueOrigin& origin, const char* key) {
    return OriginLocation(config.source_path, origin, SectionKey("vehicles", key)).Prefix();
  };
  m.body_where = where(config.vehicle_body_origin, "body");
  // A thrust-and-moment mapping's actuators are named by `thrust` and `moments`, not `rotors`.
  m.rotors_where = config.vehicle_actuation == VehicleActuation::kRotors
                       ? where(config.vehicle_rotors_origin, "rotors")
                       : where(config.vehicle_rotors_origin, "thrust / moments");
  return AdaptVehicle(m);
}

}  // namespace mjf::runner
