// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A foreign vehicle MJCF through the adapter (runner/scene AdaptVehicle, docs/VEHICLES.md). The
// input is the model's text; a first line "map BODY ROTOR..." gives the [vehicles] body and
// rotors mapping (without it: the contract's names, body "vehicle" and rotor0..rotor3).
#include <sstream>

#include "fuzz_util.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/scene/vehicle_adapter.hpp"

namespace {

mjf::fuzz::ScratchDir& Scratch() {
  static mjf::fuzz::ScratchDir dir;
  return dir;
}

// "map BODY ROTOR..." -> the mapping's body and rotors; false for any other first line.
bool ReadMapping(const std::string& line, mjf::runner::VehicleMapping* m) {
  std::istringstream words(line);
  std::string word;
  if (!(words >> word) || word != "map" || !(words >> m->body)) return false;
  m->rotors.clear();
  while (words >> word && m->rotors.size() < 16) m->rotors.push_back(word);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 64 * 1024) return 0;  // the adapter's cost grows with the model; keep runs fast
  std::string text = mjf::fuzz::AsText(data, size);
  mjf::runner::VehicleMapping m;
  m.body = "vehicle";
  m.actuator_names = {"rotor0", "rotor1", "rotor2", "rotor3"};  // pd_cascade's
  m.rotors = m.actuator_names;
  const size_t newline = text.find('\n');
  if (newline != std::string::npos && ReadMapping(text.substr(0, newline), &m)) {
    text.erase(0, newline + 1);
  }
  m.body_where = "fuzz.toml:1: [vehicles] body";
  m.rotors_where = "fuzz.toml:2: [vehicles] rotors";
  m.model_path = Scratch().Write("vehicle.xml", text);
  try {
    const mjf::runner::AdaptedVehicle adapted = mjf::runner::AdaptVehicle(m);
    (void)adapted;
  } catch (const mjf::runner::SceneError&) {
    // A refusal naming the key, the model file and the element.
  }
  return 0;
}
