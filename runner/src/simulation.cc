// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/runner/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "mjformation/core/graph.hpp"
#include "mjformation/core/shape.hpp"
#include "mjformation/runner/paths.hpp"
#include "mjformation/runner/scene.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Initial positions: the leader at leader_start, followers at follower_start or, by default,
// on a ring about the origin with at least 1.5 m between neighbours; all at the altitude.
// start_jitter adds a seeded uniform perturbation (same seed, same positions).
std::vector<std::array<double, 3>> InitialPositions(const ExperimentConfig& c) {
  std::vector<std::array<double, 3>> out;
  out.push_back({c.leader_start[0], c.leader_start[1], c.altitude});
  const double ring = std::max(2.0, 1.5 * c.followers / (2 * M_PI));
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

std::string Where(const ExperimentConfig& c, const PluginSection& s) {
  return c.source_path + (s.line > 0 ? ":" + std::to_string(s.line) : std::string()) + ": [" +
         s.section + "]";
}

// Actuator data of the vehicle model alone, in the order the attitude plugin names them.
std::vector<mjfActuatorInfo> ActuatorInfo(const mjModel* m, const mjfPlugin& plugin,
                                          const std::string& vehicle_path,
                                          std::vector<std::string>* site_names,
                                          std::vector<double>* gains) {
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const int body = mj_name2id(m, mjOBJ_BODY, "vehicle");
  std::vector<mjfActuatorInfo> out;
  for (int k = 0; k < plugin.n_actuators; ++k) {
    const char* name = plugin.actuators[k];
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, name);
    if (a < 0) {
      mj_deleteData(d);
      std::string have;
      for (int j = 0; j < m->nu; ++j) {
        have += (have.empty() ? "" : ", ") + std::string(mj_id2name(m, mjOBJ_ACTUATOR, j));
      }
      throw PluginError(
          vehicle_path + ": attitude plugin '" + plugin.name + "' drives actuator '" + name +
          "', which this vehicle model lacks (it has: " + (have.empty() ? "none" : have) + ")");
    }
    mjfActuatorInfo info{};
    std::memcpy(info.gear, m->actuator_gear + 6 * a, sizeof(info.gear));
    if (m->actuator_ctrllimited[a]) {
      info.ctrl_min = m->actuator_ctrlrange[2 * a];
      info.ctrl_max = m->actuator_ctrlrange[2 * a + 1];
    } else {
      info.ctrl_min = -std::numeric_limits<double>::infinity();
      info.ctrl_max = std::numeric_limits<double>::infinity();
    }
    info.time_constant =
        m->actuator_dyntype[a] == mjDYN_FILTER ? m->actuator_dynprm[mjNDYN * a] : 0;
    std::string site_name;
    if (m->actuator_trntype[a] == mjTRN_SITE) {
      const int site = m->actuator_trnid[2 * a];
      site_name = mj_id2name(m, mjOBJ_SITE, site);
      // Site relative to the centre of mass, in body axes: R^T (site - com).
      double rel[3];
      mju_sub3(rel, d->site_xpos + 3 * site, d->xipos + 3 * body);
      mju_mulMatTVec(info.site_pos, d->xmat + 9 * body, rel, 3, 3);
    }
    site_names->push_back(site_name);
    gains->push_back(m->actuator_gainprm[mjNGAIN * a]);
    out.push_back(info);
  }
  mj_deleteData(d);
  return out;
}

}  // namespace

std::array<double, 3> EulerZYX(const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double roll = std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
  const double pitch = std::asin(std::clamp(2 * (w * y - z * x), -1.0, 1.0));
  const double yaw = std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
  return {roll, pitch, yaw};
}

Simulation::Simulation(const ExperimentConfig& config) : config_(config) {
  registry_ = std::make_unique<PluginRegistry>(PluginSearchPath(config_.plugin_path));
  const LoadedPlugin& attitude =
      registry_->Find(config_.attitude.plugin, Where(config_, config_.attitude));
  if (attitude.descriptor->kind != MJF_KIND_ATTITUDE) {
    throw PluginError(Where(config_, config_.attitude) + " plugin: '" + config_.attitude.plugin +
                      "' is a " + KindName(attitude.descriptor->kind) +
                      " plugin; this section needs an attitude plugin");
  }
  // Attribute problems are reported before the (slower) scene compilation.
  ResolveAttributes(*attitude.descriptor, config_.attitude, config_.source_path);

  initial_positions_ = InitialPositions(config_);
  SceneRequest request;
  request.scene_path = config_.scene_path;
  request.vehicle_path = config_.model_path;
  request.positions = initial_positions_;
  request.timestep = config_.timestep;
  request.offscreen_width = std::max(config_.render.width, config_.render.video_width);
  request.offscreen_height = std::max(config_.render.height, config_.render.video_height);
  request.strip_actuators = config_.rotor_model == "wrench";
  request.disable_contacts = !config_.contacts;
  scene_xml_ = ComposeScene(request);
  model_owner_.reset(model_ = CompileModel(scene_xml_, "composed scene of " + config_.model_path));
  data_owner_.reset(data_ = mj_makeData(model_));
  total_steps_ = std::llround(config_.duration / config_.timestep);

  BindVehicles(*attitude.descriptor);
  CreatePlugins();
  CreateRealismStages();
}

Simulation::~Simulation() {
  // Plugins go first: they may hold pointers into the model.
  attitude_.clear();
  follower_guidance_.clear();
  formation_.reset();
  leader_.reset();
}

void Simulation::BindVehicles(const mjfPlugin& attitude) {
  // The vehicle model alone gives mass, inertia and actuator geometry (same for every copy).
  mjModel* vehicle = nullptr;
  {
    char error[1024] = {0};
    vehicle = mj_loadXML(config_.model_path.c_str(), nullptr, error, sizeof(error));
    if (!vehicle) throw SceneError(config_.model_path + ": MuJoCo cannot load it: " + error);
  }
  std::vector<std::string> site_names;
  std::vector<double> gains;
  std::vector<mjfActuatorInfo> actuator_info;
  const int vbody = mj_name2id(vehicle, mjOBJ_BODY, "vehicle");
  double mass = 0, inertia[3] = {0, 0, 0};
  try {
    if (vbody < 0) throw SceneError(config_.model_path + ": no body named 'vehicle'");
    actuator_info = ActuatorInfo(vehicle, attitude, config_.model_path, &site_names, &gains);
    mass = vehicle->body_subtreemass[vbody];
    std::memcpy(inertia, vehicle->body_inertia + 3 * vbody, sizeof(inertia));
    if (config_.rotor_model == "wrench") {
      for (int k = 0; k < attitude.n_actuators; ++k) {
        const int a = mj_name2id(vehicle, mjOBJ_ACTUATOR, attitude.actuators[k]);
        if (site_names[k].empty() || vehicle->actuator_gaintype[a] != mjGAIN_FIXED ||
            vehicle->actuator_biastype[a] != mjBIAS_NONE ||
            (vehicle->actuator_dyntype[a] != mjDYN_NONE &&
             vehicle->actuator_dyntype[a] != mjDYN_FILTER)) {
          throw SceneError(config_.model_path + ": [vehicles] rotor_model = \"wrench\" needs " +
                           "site actuators with fixed gain, no bias and no or filter dynamics; "
                           "actuator '" +
                           attitude.actuators[k] + "' is not one");
        }
      }
    }
  } catch (...) {
    mj_deleteModel(vehicle);
    throw;
  }
  mj_deleteModel(vehicle);
  wrench_gain_ = gains;

  actuators_per_vehicle_ = attitude.n_actuators;
  const int n = config_.followers + 1;
  bindings_.resize(n);
  states_.resize(n);
  setpoints_.resize(n);
  controls_.assign(static_cast<size_t>(n) * actuators_per_vehicle_, 0.0);
  rotor_state_.assign(controls_.size(), 0.0);
  const double gravity = mju_norm3(model_->opt.gravity);
  struct Needed {
    const char* name;
    int type;
    int dim;
    int VehicleBinding::*adr;
  };
  const Needed needed[] = {{"pos", mjSENS_FRAMEPOS, 3, &VehicleBinding::sensor_pos},
                           {"vel", mjSENS_FRAMELINVEL, 3, &VehicleBinding::sensor_vel},
                           {"quat", mjSENS_FRAMEQUAT, 4, &VehicleBinding::sensor_quat},
                           {"gyro", mjSENS_GYRO, 3, &VehicleBinding::sensor_gyro}};
  for (int i = 0; i < n; ++i) {
    VehicleBinding& b = bindings_[i];
    const std::string prefix = VehiclePrefix(i);
    b.body = mj_name2id(model_, mjOBJ_BODY, (prefix + "vehicle").c_str());
    for (const Needed& s : needed) {
      const int id = mj_name2id(model_, mjOBJ_SENSOR, (prefix + s.name).c_str());
      if (id < 0 || model_->sensor_dim[id] != s.dim || model_->sensor_type[id] != s.type) {
        throw SceneError(config_.model_path + ": the vehicle model needs a sensor named '" +
                         s.name + "' (" + std::to_string(s.dim) +
                         " values; framepos, framelinvel, framequat and gyro for pos, vel, quat, "
                         "gyro; see docs/ARCHITECTURE.md)" +
                         (id < 0 ? "; it has none" : "; it has one of another type or size"));
      }
      b.*(s.adr) = model_->sensor_adr[id];
    }
    b.actuator_info = actuator_info;
    for (int k = 0; k < actuators_per_vehicle_; ++k) {
      if (config_.rotor_model == "wrench") {
        b.sites.push_back(mj_name2id(model_, mjOBJ_SITE, (prefix + site_names[k]).c_str()));
      } else {
        b.actuators.push_back(
            mj_name2id(model_, mjOBJ_ACTUATOR, (prefix + attitude.actuators[k]).c_str()));
      }
    }
    b.info.mass = mass;
    std::memcpy(b.info.inertia, inertia, sizeof(inertia));
    b.info.gravity = gravity;
    b.info.n_actuators = actuators_per_vehicle_;
    b.info.actuators = b.actuator_info.data();
  }
}

void Simulation::CreatePlugins() {
  const int n = config_.followers + 1;
  mjfCreateContext base{};
  base.timestep = config_.timestep;
  base.n_vehicles = n;
  base.model = reinterpret_cast<const struct mjModel_*>(model_);

  // Graph and shape: checked here so a bad topology fails before any step.
  edge_from_.clear();
  for (const auto& e : config_.edges) {
    edge_from_.push_back(e.from);
    edge_to_.push_back(e.to);
    edge_weight_.push_back(e.weight);
  }
  try {
    std::vector<core::Edge> edges;
    for (const auto& e : config_.edges) edges.push_back({e.from, e.to, e.weight});
    graph_ = std::make_unique<core::Graph>(config_.followers, config_.leader_weight, edges);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(config_.source_path + ": [topology]: " + e.what());
  }
  abi_graph_ = {config_.followers,
                config_.leader_weight.data(),
                static_cast<int>(edge_from_.size()),
                edge_from_.data(),
                edge_to_.data(),
                edge_weight_.data()};
  shape_ = MakeShape(config_);
  if (shape_) abi_shape_ = core::ToAbi(*shape_);

  auto find = [&](const PluginSection& s) -> const LoadedPlugin& {
    return registry_->Find(s.plugin, Where(config_, s) + " plugin");
  };
  const LoadedPlugin& leader = find(config_.leader);
  if (leader.descriptor->kind != MJF_KIND_GUIDANCE) {
    throw PluginError(Where(config_, config_.leader) + " plugin: '" + config_.leader.plugin +
                      "' is a " + KindName(leader.descriptor->kind) +
                      " plugin; the leader needs a guidance plugin (e.g. circle, hover)");
  }
  {
    mjfCreateContext ctx = base;
    ctx.vehicle = 0;
    ctx.vehicle_info = &bindings_[0].info;
    ctx.initial_pos = initial_positions_[0].data();
    leader_ = std::make_unique<PluginInstance>(leader, config_.leader, config_.source_path, ctx);
  }
  const LoadedPlugin& formation = find(config_.formation);
  if (formation.descriptor->kind == MJF_KIND_FORMATION) {
    try {
      graph_->RequireSpanningTree();
    } catch (const std::invalid_argument& e) {
      throw ConfigError(config_.source_path + ": [topology]: " + e.what());
    }
    if (!shape_) {
      throw ConfigError(Where(config_, config_.formation) + " plugin '" + config_.formation.plugin +
                        "' needs a desired formation: add a [formation.shape] table");
    }
    try {
      // Algorithms 1 and 2, step "f_ip' = f_iv": the shape must be self-consistent.
      core::CheckShapeConsistency(*shape_, 0.0, config_.duration, 0.01, config_.shape.tolerance);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(config_.source_path + ": [formation.shape]: " + e.what());
    }
    mjfCreateContext ctx = base;
    ctx.vehicle = -1;
    ctx.graph = &abi_graph_;
    ctx.shape = &abi_shape_;
    formation_ =
        std::make_unique<PluginInstance>(formation, config_.formation, config_.source_path, ctx);
  } else if (formation.descriptor->kind == MJF_KIND_GUIDANCE) {
    // A guidance plugin per follower (e.g. hover): flies the vehicles without a formation law.
    for (int i = 1; i < n; ++i) {
      mjfCreateContext ctx = base;
      ctx.vehicle = i;
      ctx.vehicle_info = &bindings_[i].info;
      ctx.initial_pos = initial_positions_[i].data();
      follower_guidance_.push_back(
          std::make_unique<PluginInstance>(formation, config_.formation, config_.source_path, ctx));
    }
  } else {
    throw PluginError(Where(config_, config_.formation) + " plugin: '" + config_.formation.plugin +
                      "' is an attitude plugin; followers need a formation or guidance plugin");
  }
  const LoadedPlugin& attitude = find(config_.attitude);
  for (int i = 0; i < n; ++i) {
    mjfCreateContext ctx = base;
    ctx.vehicle = i;
    ctx.vehicle_info = &bindings_[i].info;
    ctx.initial_pos = initial_positions_[i].data();
    attitude_.push_back(
        std::make_unique<PluginInstance>(attitude, config_.attitude, config_.source_path, ctx));
  }
  for (auto& s : setpoints_) {
    s = mjfSetpoint{};
    s.sliding[0] = s.sliding[1] = kNaN;
  }
  for (int i = 0; i < n; ++i) {
    setpoints_[i].pos[0] = initial_positions_[i][0];
    setpoints_[i].pos[1] = initial_positions_[i][1];
    setpoints_[i].pos[2] = config_.altitude;
  }
}

void Simulation::ReadStates() {
  const mjtNum* s = data_->sensordata;
  for (size_t i = 0; i < states_.size(); ++i) {
    const VehicleBinding& b = bindings_[i];
    mjfVehicleState& st = states_[i];
    std::memcpy(st.pos, s + b.sensor_pos, sizeof(st.pos));
    std::memcpy(st.vel, s + b.sensor_vel, sizeof(st.vel));
    std::memcpy(st.quat, s + b.sensor_quat, sizeof(st.quat));
    std::memcpy(st.gyro, s + b.sensor_gyro, sizeof(st.gyro));
  }
}

void Simulation::ComputeControls() {
  mj_step1(model_, data_);
  ReadStates();
  MeasureStates();  // issue 11: the plugins see measured_states(), the truth stays in states_
  mjfStepContext ctx{};
  ctx.time = time();
  ctx.step = step_;
  ctx.timestep = config_.timestep;
  ctx.n_vehicles = n_vehicles();
  ctx.states = measured_states().data();
  ctx.setpoints = setpoints_.data();
  ctx.model = reinterpret_cast<const struct mjModel_*>(model_);
  ctx.data = reinterpret_cast<const struct mjData_*>(data_);
  auto check = [&](int rc, const PluginInstance& p, int vehicle) {
    if (rc != 0) {
      throw SimulationError(TimeTag() + ": plugin '" + p.descriptor().name + "' failed (code " +
                            std::to_string(rc) +
                            (vehicle >= 0 ? ", vehicle " + std::to_string(vehicle) : "") + ")");
    }
  };
  check(leader_->Compute(ctx), *leader_, 0);
  for (int i = 1; i < n_vehicles(); ++i) {
    mjfSetpoint& sp = setpoints_[i];
    sp.pos[2] = config_.altitude;
    sp.vel[2] = 0;
    sp.acc[2] = 0;
    sp.yaw = 0;
    sp.sliding[0] = sp.sliding[1] = kNaN;
  }
  if (formation_) {
    check(formation_->Compute(ctx), *formation_, -1);
  } else {
    for (size_t i = 0; i < follower_guidance_.size(); ++i) {
      check(follower_guidance_[i]->Compute(ctx), *follower_guidance_[i], static_cast<int>(i) + 1);
    }
  }
  // A non-finite setpoint is named here, with the plugin that wrote it, rather than surfacing
  // later as a failure of the attitude plugin that read it.
  for (int i = 0; i < n_vehicles(); ++i) {
    const mjfSetpoint& sp = setpoints_[i];
    bool finite = std::isfinite(sp.yaw);
    for (int k = 0; k < 3; ++k) {
      finite = finite && std::isfinite(sp.acc[k]) && std::isfinite(sp.pos[k]) &&
               std::isfinite(sp.vel[k]);
    }
    if (!finite) {
      const PluginInstance& writer =
          i == 0 ? *leader_ : (formation_ ? *formation_ : *follower_guidance_[i - 1]);
      throw SimulationError(TimeTag() + ": plugin '" + writer.descriptor().name +
                            "' wrote a non-finite setpoint for vehicle " + std::to_string(i));
    }
  }
  for (int i = 0; i < n_vehicles(); ++i) {
    ctx.controls = controls_.data() + static_cast<size_t>(i) * actuators_per_vehicle_;
    check(attitude_[i]->Compute(ctx), *attitude_[i], i);
    for (int k = 0; k < actuators_per_vehicle_; ++k) {
      if (!std::isfinite(ctx.controls[k])) {
        throw SimulationError(TimeTag() + ": attitude plugin '" + attitude_[i]->descriptor().name +
                              "' gave a non-finite control " + "for vehicle " + std::to_string(i) +
                              " (its setpoint or state is " + "not finite)");
      }
    }
  }
  if (config_.rotor_model == "wrench") {
    ApplyRotorWrenches();
  } else {
    for (int i = 0; i < n_vehicles(); ++i) {
      const VehicleBinding& b = bindings_[i];
      const double* c = controls_.data() + static_cast<size_t>(i) * actuators_per_vehicle_;
      for (int k = 0; k < actuators_per_vehicle_; ++k) data_->ctrl[b.actuators[k]] = c[k];
    }
  }
  ApplyWind();  // issue 11
}

// The wrench rotor model: what MuJoCo's site transmission with a filter actuator would apply,
// computed per vehicle in O(1) instead of through the dense nu x nv actuator_moment of 2.2.2.
// force = gain * act (act: first-order motor lag of the clamped control, updated in Integrate);
// the wrench gear * force acts at the site, in the site's frame.
//
// The vehicle's summed wrench (force f at its centre of mass, torque t) goes to MuJoCo as the
// generalized force J^T [f; t] in qfrc_applied, computed here from cdof over the vehicle's own
// dofs only. Handing it over as xfrc_applied instead makes MuJoCo 2.2.2 (mj_xfrcAccumulate ->
// mj_applyFT) build and clear two dense 3 x nv Jacobians per vehicle every step: O(N nv) =
// O(N^2), 97% of a step at 1000 followers (docs/PERFORMANCE.md). The maths is mj_jac's: for each
// dof j of the body's chain, J_j . [f; t] = (cdof_lin + cdof_rot x (point - subtree_com)) . f +
// cdof_rot . t; only the floating-point summation order differs.
// The small vector helpers are written out in MuJoCo's own operation order (mju_mulMatVec,
// mju_cross, mju_dot3, without FMA), so the results are bit for bit those of the mju_* calls, at a
// fraction of the cost of calling through the shared library's PLT for every rotor of every
// vehicle on every step.
namespace {
inline void MulMat3Vec(mjtNum res[3], const mjtNum m[9], const mjtNum v[3]) {
  for (int r = 0; r < 3; ++r) res[r] = m[3 * r] * v[0] + m[3 * r + 1] * v[1] + m[3 * r + 2] * v[2];
}
inline void Cross(mjtNum res[3], const mjtNum a[3], const mjtNum b[3]) {
  res[0] = a[1] * b[2] - a[2] * b[1];
  res[1] = a[2] * b[0] - a[0] * b[2];
  res[2] = a[0] * b[1] - a[1] * b[0];
}
inline mjtNum Dot3(const mjtNum a[3], const mjtNum b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
}  // namespace

void Simulation::ApplyRotorWrenches() {
  mju_zero(data_->qfrc_applied, model_->nv);
  const mjtNum* site_xpos = data_->site_xpos;
  const mjtNum* site_xmat = data_->site_xmat;
  for (int i = 0; i < n_vehicles(); ++i) {
    const VehicleBinding& b = bindings_[i];
    const mjtNum* com = data_->xipos + 3 * b.body;
    mjtNum wrench[6] = {0, 0, 0, 0, 0, 0};
    const size_t base = static_cast<size_t>(i) * actuators_per_vehicle_;
    for (int k = 0; k < actuators_per_vehicle_; ++k) {
      const mjfActuatorInfo& a = b.actuator_info[k];
      const double force =
          wrench_gain_[k] * (a.time_constant > 0
                                 ? rotor_state_[base + k]
                                 : std::clamp(controls_[base + k], a.ctrl_min, a.ctrl_max));
      const mjtNum* xmat = site_xmat + 9 * b.sites[k];
      const mjtNum* xpos = site_xpos + 3 * b.sites[k];
      mjtNum f[3], t[3], local[3], arm[3], moment[3];
      for (int j = 0; j < 3; ++j) local[j] = a.gear[j] * force;
      MulMat3Vec(f, xmat, local);
      for (int j = 0; j < 3; ++j) local[j] = a.gear[3 + j] * force;
      MulMat3Vec(t, xmat, local);
      for (int j = 0; j < 3; ++j) arm[j] = xpos[j] - com[j];
      Cross(moment, arm, f);
      for (int j = 0; j < 3; ++j) {
        wrench[j] += f[j];
        wrench[3 + j] += t[j] + moment[j];
      }
    }
    // J^T wrench at the centre of mass, over the dofs that move this body (as mj_jac walks them).
    int body = b.body;
    while (body && !model_->body_dofnum[body]) body = model_->body_parentid[body];
    if (!body) continue;
    const mjtNum* root_com = data_->subtree_com + 3 * model_->body_rootid[body];
    mjtNum offset[3];
    for (int j = 0; j < 3; ++j) offset[j] = com[j] - root_com[j];
    for (int j = model_->body_dofadr[body] + model_->body_dofnum[body] - 1; j >= 0;
         j = model_->dof_parentid[j]) {
      const mjtNum* cdof = data_->cdof + 6 * j;
      mjtNum lin[3];
      Cross(lin, cdof, offset);
      for (int k = 0; k < 3; ++k) lin[k] += cdof[3 + k];
      data_->qfrc_applied[j] += Dot3(lin, wrench) + Dot3(cdof, wrench + 3);
    }
  }
}

void Simulation::Integrate() {
  mj_step2(model_, data_);
  if (config_.rotor_model == "wrench") {
    // Motor lag, integrated like MuJoCo's filter dynamics: act += dt (ctrl - act) / tau.
    for (int i = 0; i < n_vehicles(); ++i) {
      for (int k = 0; k < actuators_per_vehicle_; ++k) {
        const mjfActuatorInfo& a = bindings_[i].actuator_info[k];
        const size_t idx = static_cast<size_t>(i) * actuators_per_vehicle_ + k;
        if (a.time_constant <= 0) continue;
        const double ctrl = std::clamp(controls_[idx], a.ctrl_min, a.ctrl_max);
        rotor_state_[idx] += config_.timestep * (ctrl - rotor_state_[idx]) / a.time_constant;
      }
    }
  }
  ++step_;
  CheckState();
}

void Simulation::CheckState() const {
  static const char* const kWarningNames[mjNWARNING] = {"near-singular inertia",
                                                        "contact list full",
                                                        "constraint list full",
                                                        "visual geoms full",
                                                        "bad qpos",
                                                        "bad qvel",
                                                        "bad qacc",
                                                        "bad ctrl"};
  for (int w = 0; w < mjNWARNING; ++w) {
    if (w == mjWARN_VGEOMFULL) continue;  // a rendering matter, not the physics'
    if (data_->warning[w].number > 0) {
      throw SimulationError(TimeTag() + ": MuJoCo warning: " + kWarningNames[w] + " (index " +
                            std::to_string(data_->warning[w].lastinfo) +
                            "); the simulation is no longer trustworthy");
    }
  }
  for (int i = 0; i < model_->nq; ++i) {
    if (!std::isfinite(data_->qpos[i])) {
      throw SimulationError(TimeTag() + ": non-finite qpos[" + std::to_string(i) + "]");
    }
  }
  for (int i = 0; i < model_->nv; ++i) {
    if (!std::isfinite(data_->qvel[i])) {
      throw SimulationError(TimeTag() + ": non-finite qvel[" + std::to_string(i) + "]");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Sensor and wind stages (issue 11). With [sensors] ideal and [wind] calm none of this runs and
// the bytes of a run are those from before these stages existed.

void Simulation::CreateRealismStages() {
  const int n = n_vehicles();
  if (config_.sensors.enabled()) {
    measured_.resize(n);
    sensors_.reserve(n);
    for (int i = 0; i < n; ++i) {
      sensors_.emplace_back(config_.sensors.params, config_.timestep,
                            realism::StreamSeed(config_.seed, i, /*stream=*/1));
    }
  }
  if (config_.wind.enabled()) {
    wind_ = std::make_unique<realism::WindField>(config_.wind.params, n, config_.timestep,
                                                 config_.seed);
    wind_now_.assign(n, {0, 0, 0});
  }
}

void Simulation::MeasureStates() {
  for (size_t i = 0; i < sensors_.size(); ++i)
    sensors_[i].Measure(step_, states_[i], &measured_[i]);
}

void Simulation::ApplyWind() {
  if (!wind_) return;
  // The wrench rotor model has just refilled qfrc_applied; otherwise nothing else writes it.
  if (config_.rotor_model != "wrench") mju_zero(data_->qfrc_applied, model_->nv);
  wind_now_ = wind_->Update(step_);
  for (int i = 0; i < n_vehicles(); ++i) {
    // Air-relative velocity from the true velocity of the vehicle's imu site (its centre of mass
    // in the vehicle models here).
    const auto f = config_.wind.drag.Force(states_[i].vel, wind_now_[i].data());
    // J^T f for a force at the centre of mass, over the dofs that move this body: the
    // translational half of ApplyRotorWrenches' loop (mj_jac's maths, without its dense 3 x nv
    // Jacobian).
    int body = bindings_[i].body;
    while (body && !model_->body_dofnum[body]) body = model_->body_parentid[body];
    if (!body) continue;
    const mjtNum* com = data_->xipos + 3 * bindings_[i].body;
    const mjtNum* root_com = data_->subtree_com + 3 * model_->body_rootid[body];
    mjtNum offset[3];
    for (int j = 0; j < 3; ++j) offset[j] = com[j] - root_com[j];
    for (int j = model_->body_dofadr[body] + model_->body_dofnum[body] - 1; j >= 0;
         j = model_->dof_parentid[j]) {
      const mjtNum* cdof = data_->cdof + 6 * j;
      mjtNum lin[3];
      Cross(lin, cdof, offset);
      for (int k = 0; k < 3; ++k) lin[k] += cdof[3 + k];
      data_->qfrc_applied[j] += Dot3(lin, f.data());
    }
  }
}
// --------------------------------------------------------------------------- end of issue 11

std::string Simulation::TimeTag() const { return fmt::format("t = {:.3f} s", time()); }

std::vector<std::pair<std::string, double>> Simulation::FormationReport() const {
  return formation_ ? formation_->Report() : std::vector<std::pair<std::string, double>>{};
}

}  // namespace mjf::runner
