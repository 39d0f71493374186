// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/vehicle_binding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "mjformation/config/source_location.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/scene/vehicle_facts.hpp"

namespace mjf::runner {
namespace {

// The id of a vehicle's element in the composed scene. A scene edited by hand (an exported one
// whose rotor was deleted) would otherwise give -1, and a control written at index -1 lands in
// another vehicle's slot; refused naming the element instead.
int SceneId(const mjModel* composed, mjtObj type, const std::string& name) {
  const int id = mj_name2id(composed, type, name.c_str());
  if (id < 0) {
    throw SceneError("the scene has no " + std::string(mju_type2Str(type)) + " named '" + name +
                     "', which its vehicle needs (was it removed from the scene?)");
  }
  return id;
}

// The vehicle model alone: mass, inertia and the attitude plugin's actuators.
struct VehicleModelInfo {
  double mass = 0;
  double inertia[3] = {0, 0, 0};
  std::vector<mjfActuatorInfo> actuators;
  std::vector<std::string> site_names;
  std::vector<double> gains;
  std::vector<std::string> undriven;  // VehicleFacts::ignored
};

// The wrench rotor model reproduces MuJoCo's site actuators only for fixed-gain, unbiased
// actuators with no or filter dynamics.
void RequireWrenchCompatible(const mjModel* vehicle, const ExperimentConfig& config,
                             const mjfPlugin& attitude, const VehicleModelInfo& info) {
  for (int k = 0; k < attitude.n_actuators; ++k) {
    const int a = mj_name2id(vehicle, mjOBJ_ACTUATOR, attitude.actuators[k]);
    if (info.site_names[k].empty() || vehicle->actuator_gaintype[a] != mjGAIN_FIXED ||
        vehicle->actuator_biastype[a] != mjBIAS_NONE ||
        (vehicle->actuator_dyntype[a] != mjDYN_NONE &&
         vehicle->actuator_dyntype[a] != mjDYN_FILTER)) {
      throw SceneError(config.model_path + ": [vehicles] rotor_model = \"wrench\" needs " +
                       "site actuators with fixed gain, no bias and no or filter dynamics; "
                       "actuator '" +
                       attitude.actuators[k] + "' is not one");
    }
  }
}

// [vehicles] thrust and moments: a gear that does not fit its role (MisfitThrustMomentRole) is
// refused naming the key and the model's actuator, before the plugin sees it.
void RequireThrustAndMoments(const ExperimentConfig& config, const VehicleFacts& facts) {
  const int k = MisfitThrustMomentRole(facts);
  if (k < 0) return;
  const bool thrust = k == 0;
  const std::string where =
      OriginLocation(config.source_path,
                     thrust ? config.vehicle_rotors_origin : config.vehicle_moments_origin,
                     SectionKey("vehicles", thrust ? "thrust" : "moments"))
          .Prefix();
  throw SceneError(where + ": " + config.model_path + ": actuator '" + config.vehicle_rotors[k] +
                   "' is mapped as the " + ThrustMomentRole(k) + " but its gear is \"" +
                   GearText(facts.info[k].gear) + "\" (the role needs gear entry " +
                   std::to_string(ThrustMomentGearEntry(k)) + " alone non-zero)");
}

// The reader's facts of the vehicle model alone, refusals prefixed with the vehicle file (and,
// for an actuator, the attitude plugin that names it).
VehicleModelInfo FactsOf(const mjModel* vehicle, const ExperimentConfig& config,
                         const mjfPlugin& attitude) {
  std::vector<std::string> names(attitude.actuators, attitude.actuators + attitude.n_actuators);
  VehicleFacts facts;
  try {
    facts = ReadVehicleFacts(vehicle, "vehicle", names);
  } catch (const VehicleFactError& e) {
    if (e.key() == "body") throw SceneError(config.model_path + ": " + e.what());
    throw PluginError(config.model_path + ": attitude plugin '" + attitude.name + "': " + e.what());
  }
  if (config.vehicle_actuation == VehicleActuation::kThrustMoments) {
    RequireThrustAndMoments(config, facts);
  }
  VehicleModelInfo info;
  info.mass = facts.mass;
  std::memcpy(info.inertia, facts.inertia, sizeof(info.inertia));
  info.actuators = facts.info;
  info.gains = facts.gains;
  info.undriven = facts.ignored;
  for (int site : facts.sites) {
    const char* name = site < 0 ? nullptr : mj_id2name(vehicle, mjOBJ_SITE, site);
    info.site_names.push_back(name ? name : "");
  }
  return info;
}

VehicleModelInfo ReadVehicleModel(const ExperimentConfig& config, const mjfPlugin& attitude,
                                  const std::string& vehicle_xml) {
  char error[1024] = {0};
  mjModel* vehicle = vehicle_xml.empty()
                         ? mj_loadXML(config.model_path.c_str(), nullptr, error, sizeof(error))
                         : CompileModel(vehicle_xml, config.model_path + " (adapted)");
  if (!vehicle) throw SceneError(config.model_path + ": MuJoCo cannot load it: " + error);
  VehicleModelInfo info;
  try {
    info = FactsOf(vehicle, config, attitude);
    if (config.rotor_model == RotorModel::kWrench) {
      RequireWrenchCompatible(vehicle, config, attitude, info);
    }
  } catch (...) {
    mj_deleteModel(vehicle);
    throw;
  }
  mj_deleteModel(vehicle);
  return info;
}

// Sensor addresses of vehicle `prefix` in the composed model, whose names read `names`.
void BindSensors(const mjModel* m, const std::string& prefix, const SceneNames& names,
                 const std::string& model_path, VehicleBinding* b) {
  struct Needed {
    const char* name;
    int type;
    int dim;
    int VehicleBinding::*adr;
  };
  static const Needed kNeeded[] = {{"pos", mjSENS_FRAMEPOS, 3, &VehicleBinding::sensor_pos},
                                   {"vel", mjSENS_FRAMELINVEL, 3, &VehicleBinding::sensor_vel},
                                   {"quat", mjSENS_FRAMEQUAT, 4, &VehicleBinding::sensor_quat},
                                   {"gyro", mjSENS_GYRO, 3, &VehicleBinding::sensor_gyro}};
  for (const Needed& s : kNeeded) {
    const int id = mj_name2id(m, mjOBJ_SENSOR, names(prefix + s.name).c_str());
    if (id < 0 || m->sensor_dim[id] != s.dim || m->sensor_type[id] != s.type) {
      throw SceneError(model_path + ": the vehicle model needs a sensor named '" + s.name + "' (" +
                       std::to_string(s.dim) +
                       " values; framepos, framelinvel, framequat and gyro for pos, vel, quat, "
                       "gyro; see docs/ARCHITECTURE.md)" +
                       (id < 0 ? "; it has none" : "; it has one of another type or size"));
    }
    b->*(s.adr) = m->sensor_adr[id];
  }
}

}  // namespace

std::vector<std::array<double, 3>> InitialPositions(const ExperimentConfig& c) {
  std::vector<std::array<double, 3>> out;
  out.push_back({c.leader_start[0], c.leader_start[1], c.altitude});
  // Default start: a ring about the origin, at least 2 m in radius, whose neighbours are at least
  // 1.5 m apart (chord 2 r sin(pi / n) = 1.5 m, not the arc length, which is longer).
  const double ring = c.followers < 2 ? 2.0 : std::max(2.0, 0.75 / std::sin(M_PI / c.followers));
  std::mt19937_64 rng(c.seed);
  for (int i = 0; i < c.followers; ++i) {
    std::array<double, 3> p;
    if (!c.follower_start.empty()) {
      p = {c.follower_start[i][0], c.follower_start[i][1], c.altitude};
    } else {
      const double a = 2 * M_PI * i / c.followers;
      p = {ring * std::cos(a), ring * std::sin(a), c.altitude};
    }
    for (int k = 0; k < 2; ++k) {
      // Uniform in [-jitter, jitter] from raw 53-bit draws: the same on every platform.
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
      p[k] += c.start_jitter * (2 * u - 1);
    }
    out.push_back(p);
  }
  return out;
}

namespace {

VehicleBindings Bind(const mjModel* composed, const ExperimentConfig& config,
                     const mjfPlugin& attitude, const std::string& vehicle_xml, int first,
                     int count, bool bind_ids, const SceneNames& names) {
  const VehicleModelInfo vehicle = ReadVehicleModel(config, attitude, vehicle_xml);
  VehicleBindings out;
  out.wrench_gain = vehicle.gains;
  out.actuators_per_vehicle = attitude.n_actuators;
  out.undriven_actuators = vehicle.undriven;
  const int n = count < 0 ? config.followers + 1 : count;
  out.vehicles.resize(n);
  const double gravity = mju_norm3(composed->opt.gravity);
  for (int i = 0; i < n; ++i) {
    VehicleBinding& b = out.vehicles[i];
    const std::string prefix = VehiclePrefix(first + i);
    b.actuator_info = vehicle.actuators;
    for (int k = 0; bind_ids && k < attitude.n_actuators; ++k) {
      if (config.rotor_model == RotorModel::kWrench) {
        b.sites.push_back(SceneId(composed, mjOBJ_SITE, names(prefix + vehicle.site_names[k])));
      } else {
        b.actuators.push_back(
            SceneId(composed, mjOBJ_ACTUATOR, names(prefix + attitude.actuators[k])));
      }
    }
    b.info.mass = vehicle.mass;
    std::memcpy(b.info.inertia, vehicle.inertia, sizeof(vehicle.inertia));
    b.info.gravity = gravity;
    b.info.n_actuators = attitude.n_actuators;
    b.info.actuators = b.actuator_info.data();
    b.info.actuation = config.vehicle_actuation == VehicleActuation::kThrustMoments
                           ? MJF_ACTUATION_THRUST_MOMENTS
                           : MJF_ACTUATION_ROTORS;
    if (!bind_ids) continue;
    b.body = SceneId(composed, mjOBJ_BODY, names(prefix + "vehicle"));
    BindSensors(composed, prefix, names, config.model_path, &b);
  }
  return out;
}

}  // namespace

VehicleBindings BindVehicles(const mjModel* composed, const ExperimentConfig& config,
                             const mjfPlugin& attitude, const std::string& vehicle_xml, int first,
                             int count, const SceneNames& names) {
  return Bind(composed, config, attitude, vehicle_xml, first, count, true, names);
}

VehicleBindings DescribeVehicles(const mjModel* model, const ExperimentConfig& config,
                                 const mjfPlugin& attitude, const std::string& vehicle_xml) {
  return Bind(model, config, attitude, vehicle_xml, 0, -1, false, {});
}

void ReadTrueStates(const mjData* data, const VehicleBindings& bindings,
                    std::vector<mjfVehicleState>* states) {
  const mjtNum* s = data->sensordata;
  for (size_t i = 0; i < states->size(); ++i) {
    const VehicleBinding& b = bindings.vehicles[i];
    mjfVehicleState& st = (*states)[i];
    std::memcpy(st.pos, s + b.sensor_pos, sizeof(st.pos));
    std::memcpy(st.vel, s + b.sensor_vel, sizeof(st.vel));
    std::memcpy(st.quat, s + b.sensor_quat, sizeof(st.quat));
    std::memcpy(st.gyro, s + b.sensor_gyro, sizeof(st.gyro));
  }
}

}  // namespace mjf::runner
