// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapt/vehicle_renaming.hpp"

#include <cstring>
#include <iterator>
#include <set>

#include "mjcf_util.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using mjcf::Str;
using tinyxml2::XMLElement;

const char* const kContractSensors[] = {"pos", "vel", "quat", "gyro"};

// What names an element of one kind: the tags that carry such a name, the attributes that refer
// to it, and the objtype/reftype values that mean it.
struct NameKind {
  std::set<std::string> tags;
  std::set<std::string> attributes;
  std::set<std::string> objtypes;
};

NameKind KindOf(const std::string& kind) {
  NameKind k;
  if (kind == "actuator") {
    k.tags = {std::begin(kActuatorTags), std::end(kActuatorTags)};
  } else {
    k.tags = {kind};
  }
  for (const auto& ref : mjcf::kReferenceAttributes) {
    if (ref.kind == kind) k.attributes.insert(ref.name);
  }
  k.objtypes = {kind};
  if (kind == "body") k.objtypes.insert("xbody");
  return k;
}

void Rename(XMLElement* e, const NameKind& k, const std::string& from, const std::string& to) {
  if (k.tags.count(e->Name()) && e->Attribute("name", from.c_str())) {
    e->SetAttribute("name", to.c_str());
  }
  for (const auto& a : k.attributes) {
    if (e->Attribute(a.c_str(), from.c_str())) e->SetAttribute(a.c_str(), to.c_str());
  }
  if (e->Attribute("objname", from.c_str()) && k.objtypes.count(Str(e->Attribute("objtype")))) {
    e->SetAttribute("objname", to.c_str());
  }
  if (e->Attribute("refname", from.c_str()) && k.objtypes.count(Str(e->Attribute("reftype")))) {
    e->SetAttribute("refname", to.c_str());
  }
  for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    Rename(c, k, from, to);
  }
}

}  // namespace

void RenameElement(XMLElement* root, const std::string& kind, const std::string& from,
                   const std::string& to) {
  Rename(root, KindOf(kind), from, to);
}

void RenameVehicleBody(XMLElement* root, const XMLElement* body, const std::string& name,
                       const std::string& model_path, const std::string& where,
                       std::vector<std::string>* notes) {
  if (name == "vehicle") return;
  if (mjcf::HasNamed(body, "body", "vehicle")) {
    throw SceneError(where + ": " + model_path + ": body '" + name +
                     "' contains a body named 'vehicle', the name the contract gives the "
                     "vehicle itself: rename it");
  }
  RenameElement(root, "body", name, "vehicle");
  notes->push_back("renamed body '" + name + "' to 'vehicle'");
}

void MakeRoomForContractNames(XMLElement* root, std::vector<std::string>* notes) {
  if (mjcf::HasNamed(root, "site", "imu")) {
    RenameElement(root, "site", "imu", "model_imu");
    notes->push_back(
        "renamed the model's site 'imu' to 'model_imu' (the contract's 'imu' sits at the "
        "centre of mass)");
  }
  if (XMLElement* s = root->FirstChildElement("sensor")) {
    for (XMLElement* e = s->FirstChildElement(); e; e = e->NextSiblingElement()) {
      for (const char* n : kContractSensors) {
        if (e->Attribute("name", n)) {
          e->SetAttribute("name", (std::string("model_") + n).c_str());
          notes->push_back(std::string("renamed the model's sensor '") + n + "' to 'model_" + n +
                           "'");
        }
      }
    }
  }
}

}  // namespace mjf::runner
