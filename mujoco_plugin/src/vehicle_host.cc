// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "vehicle_host.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/control/control_wiring.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "scene_files.hpp"
#include "swarm_host.hpp"

namespace mjf::native {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A TOML basic string of `text`, escaped by the TOML library: a plugin_path may hold any
// character, a quote included.
std::string TomlString(const std::string& text) {
  std::ostringstream out;
  out << toml::value<std::string>(text);
  return out.str();
}

// The experiment parser's messages name sections and keys of the text below; the MJCF's author
// wrote attributes, so each section is named by the attribute that gave it.
std::string NamingAttributes(std::string message) {
  const std::pair<const char*, const char*> kNames[] = {
      {"<config key=\"leader\">", "<config key=\"guidance\">"},
      {"[leader]", "<config key=\"guidance\">"},
      {"[attitude]", "<config key=\"attitude\">"},
      {"[run] plugin_path", "<config key=\"plugin_path\">"},
  };
  for (const auto& [section, attribute] : kNames) {
    for (size_t at = message.find(section); at != std::string::npos;
         at = message.find(section, at + std::strlen(attribute))) {
      message.replace(at, std::strlen(section), attribute);
    }
  }
  return message;
}

// The two sections through the experiment parser (its names, defaults, checks and messages),
// inside the smallest experiment it accepts; only [leader] (the guidance) and [attitude] are
// used. Each attribute is read as one table of its own (ConfigFromPairs), never spliced into
// text: a value cannot open another section.
runner::ExperimentConfig Sections(const VehicleHostConfig& c) {
  std::vector<std::pair<std::string, std::string>> pairs = {
      {"leader", c.guidance.empty() ? "plugin = \"hover\"" : c.guidance},
      {"attitude", c.attitude},
      {"formation", "plugin = \"hover\""},
      {"vehicles", "followers = 1"},
      {"topology", "leader_links = [1]"}};
  if (!c.plugin_path.empty()) {
    pairs.emplace_back("run", "plugin_path = [" + TomlString(c.plugin_path) + "]");
  }
  return ConfigFromPairs(pairs, c.where);
}

// Actuator `a`'s facts: MuJoCo 4 keeps per-actuator arrays by actuator id, gear by the
// actuator's first force output (actuator_outadr) and ctrlrange by its first control
// (actuator_ctrladr); a rotor has one of each.
mjfActuatorInfo ActuatorInfo(const mjModel* m, int a) {
  mjfActuatorInfo info{};
  const int out = m->actuator_outadr[a], ctrl = m->actuator_ctrladr[a];
  std::memcpy(info.gear, m->actuator_gear + 6 * out, sizeof(info.gear));
  info.ctrl_min = m->actuator_ctrllimited[ctrl] ? m->actuator_ctrlrange[2 * ctrl]
                                                : -std::numeric_limits<double>::infinity();
  info.ctrl_max = m->actuator_ctrllimited[ctrl] ? m->actuator_ctrlrange[2 * ctrl + 1]
                                                : std::numeric_limits<double>::infinity();
  info.time_constant = m->actuator_dyntype[a] == mjDYN_FILTER ? m->actuator_dynprm[mjNDYN * a] : 0;
  return info;
}

// Rotor site `site` relative to the centre of mass of `body`, in body axes. site_pos is in the
// frame of the site's own body; a site on a body inside the vehicle is carried out through each
// fixed frame on the way (p <- body_pos + R(body_quat) p). A body on the way that a joint moves
// gives no fixed arm, and is refused; so is a site outside the vehicle.
void RotorArm(const mjModel* m, const std::string& where, int body, int site, double out[3]) {
  const char* site_name = mj_id2name(m, mjOBJ_SITE, site);
  const std::string named = "site '" + std::string(site_name ? site_name : "") + "'";
  mjtNum p[3];
  mju_copy3(p, m->site_pos + 3 * site);
  for (int b = m->site_bodyid[site]; b != body; b = m->body_parentid[b]) {
    const char* b_name = mj_id2name(m, mjOBJ_BODY, b);
    if (b == 0) {
      throw std::runtime_error(where + ": <config key=\"actuators\">: a rotor acts on " + named +
                               ", which is not on the vehicle's body or a body inside it");
    }
    if (m->body_jntnum[b] > 0) {
      throw std::runtime_error(where + ": <config key=\"actuators\">: a rotor acts on " + named +
                               " of body '" + (b_name ? b_name : "") +
                               "', which a joint moves: a rotor's arm must be fixed to the body");
    }
    mjtNum turned[3];
    mju_rotVecQuat(turned, p, m->body_quat + 4 * b);
    mju_add3(p, turned, m->body_pos + 3 * b);
  }
  mju_sub3(out, p, m->body_ipos + 3 * body);
}

// What the runner's vehicle binding reads of each driven actuator (gear, control range, motor
// lag, site relative to the centre of mass in body axes), from the compiled model.
void ReadActuators(const mjModel* m, const std::string& where, int body,
                   const std::vector<std::string>& names, std::vector<int>* ids,
                   std::vector<mjfActuatorInfo>* infos) {
  for (const std::string& name : names) {
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str());
    if (a < 0) {
      throw std::runtime_error(where + ": <config key=\"actuators\">: no actuator named '" + name +
                               "' in this model");
    }
    if (m->actuator_ctrlnum[a] != 1 || m->actuator_outnum[a] != 1) {
      throw std::runtime_error(where + ": <config key=\"actuators\">: actuator '" + name +
                               "' takes " + std::to_string(m->actuator_ctrlnum[a]) +
                               " controls and has " + std::to_string(m->actuator_outnum[a]) +
                               " force outputs; a rotor has one of each: name the rotors");
    }
    ids->push_back(a);
    mjfActuatorInfo info = ActuatorInfo(m, a);
    if (m->actuator_trntype[a] == mjTRN_SITE) {
      RotorArm(m, where, body, m->actuator_trnid[2 * a], info.site_pos);
    }
    infos->push_back(info);
  }
}

// The diagonal of the body-frame inertia tensor J_body = R(iquat) diag(body_inertia) R(iquat)^T:
// MuJoCo gives the principal moments in the principal-axis frame (body_iquat), our controllers
// work in body axes (state.gyro, actuator sites), and the plugin ABI carries three moments, so
// the products of inertia of a body whose principal axes are not its own are dropped.
void BodyAxisInertia(const mjModel* m, int body, double out[3]) {
  mjtNum r[9];
  mju_quat2Mat(r, m->body_iquat + 4 * body);
  const mjtNum* principal = m->body_inertia + 3 * body;
  for (int i = 0; i < 3; ++i) {
    // J_ii = sum_k R_ik^2 I_k
    out[i] = 0;
    for (int k = 0; k < 3; ++k) out[i] += r[3 * i + k] * r[3 * i + k] * principal[k];
  }
}

}  // namespace

const std::vector<const char*>& VehicleAttributes() {
  static const std::vector<const char*> kNames = {"attitude", "guidance", "body", "actuators",
                                                  "plugin_path"};
  return kNames;
}

VehicleHostConfig VehicleConfigFromModel(const mjModel* m, int instance, const char* plugin_name) {
  VehicleHostConfig c;
  const char* name = mj_id2name(m, mjOBJ_PLUGIN, instance);
  c.where = std::string("MJCF plugin '") + plugin_name + "' instance '" +
            (name && name[0] ? name : std::to_string(instance)) + "'";
  auto get = [&](const char* key) {
    const char* v = mj_getPluginConfig(m, instance, key);
    return std::string(v ? v : "");
  };
  c.attitude = get("attitude");
  c.guidance = get("guidance");
  c.body = get("body");
  c.actuators = Words(get("actuators"));
  c.plugin_path = get("plugin_path");
  if (c.attitude.empty()) {
    throw std::runtime_error(c.where +
                             ": <config key=\"attitude\">: missing: name the plugin, "
                             "e.g. value=\"plugin = 'geometric'\"");
  }
  if (c.body.empty()) {
    throw std::runtime_error(c.where + ": <config key=\"body\">: missing: the vehicle's body");
  }
  return c;
}

struct VehicleHost::Impl {
  VehicleHostConfig config;
  runner::ExperimentConfig sections;
  std::unique_ptr<runner::PluginRegistry> registry;
  int body = -1;
  std::vector<int> actuators;
  std::vector<mjfActuatorInfo> actuator_info;
  mjfVehicleInfo info{};
  double initial_pos[3] = {0, 0, 0};
  std::unique_ptr<runner::PluginInstance> guidance;
  std::unique_ptr<runner::PluginInstance> attitude;
  mjfSetpoint setpoint{};
  std::vector<double> controls;
  char error[512] = {0};
};

// What the runner's vehicle binding reads of a vehicle model (mass, principal inertia, actuator
// geometry), read here from the compiled model's own fields: the model is the user's scene.
VehicleHost::VehicleHost(const mjModel* m, VehicleHostConfig config)
    : impl_(std::make_unique<Impl>()) {
  impl_->config = std::move(config);
  try {
    Build(m);
  } catch (const std::exception& e) {
    // The parser and the plugin loader name lines of the text Sections built; the author of
    // the MJCF wrote attributes.
    throw std::runtime_error(NamingAttributes(WithoutLine(e.what(), impl_->config.where)));
  }
}

void VehicleHost::Build(const mjModel* m) {
  Impl& s = *impl_;
  const std::string& where = s.config.where;
  s.sections = Sections(s.config);
  s.registry =
      std::make_unique<runner::PluginRegistry>(NativePluginSearchPath(s.sections.plugin_path));
  const runner::LoadedPlugin& attitude =
      runner::FindPlugin(*s.registry, s.sections, s.sections.attitude, {MJF_KIND_ATTITUDE},
                         "this key needs an attitude plugin");
  const runner::LoadedPlugin& guidance =
      runner::FindPlugin(*s.registry, s.sections, s.sections.leader, {MJF_KIND_GUIDANCE},
                         "this key needs a guidance plugin");
  s.body = mj_name2id(m, mjOBJ_BODY, s.config.body.c_str());
  if (s.body <= 0) {
    throw std::runtime_error(where + ": <config key=\"body\">: no body named '" + s.config.body +
                             "' in this model");
  }
  const mjfPlugin& d = *attitude.descriptor;
  if (static_cast<int>(s.config.actuators.size()) != d.n_actuators) {
    std::string names;
    for (int k = 0; k < d.n_actuators; ++k) names += (k ? ", " : "") + std::string(d.actuators[k]);
    throw std::runtime_error(where + ": <config key=\"actuators\">: attitude plugin '" + d.name +
                             "' drives " + std::to_string(d.n_actuators) + " actuators (" + names +
                             "); name this model's, in that order");
  }
  ReadActuators(m, where, s.body, s.config.actuators, &s.actuators, &s.actuator_info);
  s.info.mass = m->body_subtreemass[s.body];
  BodyAxisInertia(m, s.body, s.info.inertia);
  s.info.gravity = std::sqrt(mju_dot3(m->opt.gravity, m->opt.gravity));
  s.info.n_actuators = d.n_actuators;
  s.info.actuators = s.actuator_info.data();
  s.info.actuation = MJF_ACTUATION_ROTORS;
  std::memcpy(s.initial_pos, m->body_pos + 3 * s.body, sizeof(s.initial_pos));

  mjfCreateContext ctx{};
  ctx.timestep = m->opt.timestep;
  ctx.vehicle = 0;
  ctx.n_vehicles = 1;
  ctx.vehicle_info = &s.info;
  ctx.initial_pos = s.initial_pos;
  ctx.model = reinterpret_cast<const struct mjModel_*>(m);
  s.guidance = std::make_unique<runner::PluginInstance>(guidance, s.sections.leader, where, ctx);
  s.attitude = std::make_unique<runner::PluginInstance>(attitude, s.sections.attitude, where, ctx);
  s.setpoint.sliding[0] = s.setpoint.sliding[1] = kNaN;
  for (int k = 0; k < 3; ++k) s.setpoint.pos[k] = s.initial_pos[k];
  s.controls.assign(d.n_actuators, 0.0);
}

VehicleHost::~VehicleHost() = default;

namespace {
constexpr size_t kSetpointDoubles = sizeof(mjfSetpoint) / sizeof(double);
static_assert(sizeof(mjfSetpoint) == 12 * sizeof(double), "mjfSetpoint holds doubles only");
}  // namespace

size_t VehicleHost::state_size() const {
  return kSetpointDoubles + impl_->guidance->state_size() + impl_->attitude->state_size();
}

void VehicleHost::GetState(double* out) const {
  std::memcpy(out, &impl_->setpoint, sizeof(mjfSetpoint));
  out += kSetpointDoubles;
  impl_->guidance->GetState(out);
  impl_->attitude->GetState(out + impl_->guidance->state_size());
}

void VehicleHost::SetState(const double* in) {
  std::memcpy(&impl_->setpoint, in, sizeof(mjfSetpoint));
  in += kSetpointDoubles;
  impl_->guidance->SetState(in);
  impl_->attitude->SetState(in + impl_->guidance->state_size());
}

void VehicleHost::Tick(int64_t step, const mjModel* m, const mjData* d, double* controls) {
  Impl& s = *impl_;
  // The body's state as the vehicle contract's sensors report it: position and world velocity
  // of the body frame, attitude, body-frame rates. mjOBJ_XBODY is the body frame (xpos, xmat);
  // mjOBJ_BODY would be the principal-axis frame at the centre of mass (xipos, ximat).
  mjfVehicleState state{};
  std::memcpy(state.pos, d->xpos + 3 * s.body, sizeof(state.pos));
  std::memcpy(state.quat, d->xquat + 4 * s.body, sizeof(state.quat));
  mjtNum world[6], local[6];
  mj_objectVelocity(m, d, mjOBJ_XBODY, s.body, world, 0);
  mj_objectVelocity(m, d, mjOBJ_XBODY, s.body, local, 1);
  std::memcpy(state.vel, world + 3, sizeof(state.vel));
  std::memcpy(state.gyro, local, sizeof(state.gyro));
  mjfStepContext ctx{};
  // The tick's time is its step's (as the runner's), never d->time: an RK4 stage or a
  // perturbed evaluation has a time of its own.
  ctx.time = static_cast<double>(step) * m->opt.timestep;
  ctx.step = step;
  ctx.timestep = m->opt.timestep;
  ctx.n_vehicles = 1;
  ctx.states = &state;
  ctx.setpoints = &s.setpoint;
  ctx.model = reinterpret_cast<const struct mjModel_*>(m);
  ctx.data = reinterpret_cast<const struct mjData_*>(d);
  ctx.error = s.error;
  ctx.error_size = sizeof(s.error);
  for (runner::PluginInstance* p : {s.guidance.get(), s.attitude.get()}) {
    s.error[0] = '\0';
    ctx.controls = p == s.attitude.get() ? s.controls.data() : nullptr;
    if (p->Compute(ctx) != 0) {
      throw std::runtime_error(s.config.where + ": plugin '" + p->descriptor().name +
                               "' failed at t = " + std::to_string(ctx.time) +
                               " s: " + (s.error[0] ? s.error : "no reason given"));
    }
  }
  for (size_t k = 0; k < s.actuators.size(); ++k) controls[s.actuators[k]] = s.controls[k];
}

}  // namespace mjf::native
