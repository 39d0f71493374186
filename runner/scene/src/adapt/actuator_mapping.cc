// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapt/actuator_mapping.hpp"

#include <algorithm>

#include "adapt/vehicle_renaming.hpp"
#include "mjcf_util.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using mjcf::Str;
using tinyxml2::XMLElement;

std::vector<XMLElement*> Actuators(XMLElement* root) {
  std::vector<XMLElement*> out;
  if (XMLElement* s = root->FirstChildElement("actuator")) {
    for (XMLElement* a = s->FirstChildElement(); a; a = a->NextSiblingElement()) out.push_back(a);
  }
  return out;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The model's actuator elements for the mapped rotor names, in the mapping's order; each
// refused (missing, repeated, not on the vehicle) with the experiment key.
std::vector<XMLElement*> FindRotors(XMLElement* root, const XMLElement* body,
                                    const VehicleMapping& m) {
  std::vector<XMLElement*> actuators = Actuators(root);
  std::string have;
  for (XMLElement* a : actuators) have += (have.empty() ? "" : ", ") + Str(a->Attribute("name"));
  std::vector<XMLElement*> rotor(m.rotors.size(), nullptr);
  for (size_t k = 0; k < m.rotors.size(); ++k) {
    for (size_t j = 0; j < k; ++j) {
      if (m.rotors[j] == m.rotors[k]) {
        throw SceneError(m.rotors_where + ": rotor '" + m.rotors[k] +
                         "' is listed twice; each rotor of " + m.model_path + " once");
      }
    }
    for (XMLElement* a : actuators) {
      if (a->Attribute("name", m.rotors[k].c_str())) rotor[k] = a;
    }
    if (!rotor[k]) {
      throw SceneError(m.rotors_where + ": " + m.model_path + " has no actuator named '" +
                       m.rotors[k] + "' (its actuators: " + (have.empty() ? "none" : have) + ")");
    }
    if (const char* site = rotor[k]->Attribute("site");
        site && !mjcf::HasNamed(body, "site", site)) {
      throw SceneError(m.rotors_where + ": " + mjcf::At(m.model_path, rotor[k]) + ": rotor '" +
                       m.rotors[k] + "' acts on site '" + site + "', which is not on body '" +
                       m.body + "'");
    }
  }
  return rotor;
}

}  // namespace

void MapRotors(XMLElement* root, const XMLElement* body, const VehicleMapping& m,
               std::vector<std::string>* notes) {
  const auto& want = m.actuator_names;
  if (m.rotors.size() != want.size()) {
    throw SceneError(m.rotors_where + ": lists " + std::to_string(m.rotors.size()) + " rotors of " +
                     m.model_path + "; the attitude plugin drives " + std::to_string(want.size()) +
                     " (" + JoinNames(want) + "), in that order");
  }
  const std::vector<XMLElement*> rotor = FindRotors(root, body, m);
  // A non-rotor actuator that already has a contract name steps aside.
  for (XMLElement* a : Actuators(root)) {
    if (std::find(rotor.begin(), rotor.end(), a) != rotor.end()) continue;
    const std::string n = Str(a->Attribute("name"));
    if (std::find(want.begin(), want.end(), n) != want.end()) {
      RenameElement(root, "actuator", n, "model_" + n);
      notes->push_back("renamed actuator '" + n + "' (not a rotor) to 'model_" + n + "'");
    }
  }
  // Two passes, so that a permutation of names (rotors = ["rotor1", "rotor0", ...]) works.
  for (size_t k = 0; k < rotor.size(); ++k) {
    RenameElement(root, "actuator", m.rotors[k], "mjf_rotor_tmp_" + std::to_string(k));
  }
  for (size_t k = 0; k < rotor.size(); ++k) {
    RenameElement(root, "actuator", "mjf_rotor_tmp_" + std::to_string(k), want[k]);
    if (m.rotors[k] != want[k]) {
      notes->push_back("renamed actuator '" + m.rotors[k] + "' to '" + want[k] + "'");
    }
  }
}

}  // namespace mjf::runner
