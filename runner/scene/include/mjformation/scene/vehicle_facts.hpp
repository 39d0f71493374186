// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What an attitude controller needs to know of a vehicle (mass, inertia, each rotor's gear,
// control range, motor lag and arm), read from a compiled model alone: no file, no mjData. The
// one reader of both faces: the runner's vehicle binding (on the vehicle model) and the native
// plugin mjformation.attitude (on the user's scene), so a vehicle one face refuses the other
// refuses with the same reason.
#ifndef MJFORMATION_SCENE_VEHICLE_FACTS_HPP_
#define MJFORMATION_SCENE_VEHICLE_FACTS_HPP_

#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mjf::runner {

// A vehicle the reader refuses. `key()` is what the refusal is about: "body" (the vehicle's
// body) or "actuators" (a driven actuator); what() is the reason alone, which each face prefixes
// with its own place (the vehicle file; the plugin instance and its <config> key).
class VehicleFactError : public std::runtime_error {
 public:
  VehicleFactError(std::string key, const std::string& reason)
      : std::runtime_error(reason), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

struct VehicleFacts {
  int body = -1;
  double mass = 0;  // of the body's subtree (kg)
  // Diagonal of the inertia tensor in body axes, J = R(body_iquat) diag(body_inertia) R^T
  // (kg m^2): MuJoCo gives principal moments in the principal-axis frame; our controllers work in
  // body axes, and the plugin ABI carries three moments (the products of inertia are dropped).
  double inertia[3] = {0, 0, 0};
  std::vector<int> actuators;         // ids, in the order named
  std::vector<int> sites;             // the site each acts at; -1: not a site transmission
  std::vector<mjfActuatorInfo> info;  // gear, control range, motor lag, arm (plugin.h)
  std::vector<double> gains;          // gainprm[0] of each
  // The actuators that act on the vehicle but were not named (a gimbal's servo, a gripper):
  // left alone, named here so a face can say so.
  std::vector<std::string> ignored;
};

// Reads body `body_name` and the actuators `actuators` (in the attitude plugin's order) of
// `m`. Refuses, with a VehicleFactError: no such body; a body no joint moves (welded to the
// world); a missing actuator (naming those the model has); an actuator with more than one control
// or force output; a rotor site outside the vehicle or on a body a joint moves inside it.
VehicleFacts ReadVehicleFacts(const mjModel* m, const std::string& body_name,
                              const std::vector<std::string>& actuators);

// A thrust-and-moments vehicle (MJF_ACTUATION_THRUST_MOMENTS): actuator 0 pushes along body z
// only, actuator 1 + i turns about body axis i only (either sign). The first of the four whose
// gear does not fit its role, or -1; then ThrustMomentRole(k) names the role and
// ThrustMomentGearEntry(k) the one gear entry it may use.
int MisfitThrustMomentRole(const VehicleFacts& facts);
const char* ThrustMomentRole(int k);
int ThrustMomentGearEntry(int k);
// "g0 g1 g2 g3 g4 g5", for a refusal.
std::string GearText(const double gear[6]);

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_VEHICLE_FACTS_HPP_
