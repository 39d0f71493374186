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
#include "mjformation/scene/vehicle_facts.hpp"
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

// The vehicle's facts through the one reader (vehicle_facts.hpp), each refusal named by the
// <config> key it is about; with actuation = "thrust_moments", each gear must fit its role.
runner::VehicleFacts ReadFacts(const mjModel* m, const VehicleHostConfig& c, const mjfPlugin& d) {
  const std::string& where = c.where;
  if (static_cast<int>(c.actuators.size()) != d.n_actuators) {
    std::string names;
    for (int k = 0; k < d.n_actuators; ++k) names += (k ? ", " : "") + std::string(d.actuators[k]);
    throw std::runtime_error(where + ": <config key=\"actuators\">: attitude plugin '" + d.name +
                             "' drives " + std::to_string(d.n_actuators) + " actuators (" + names +
                             "); name this model's, in that order");
  }
  runner::VehicleFacts facts;
  try {
    facts = runner::ReadVehicleFacts(m, c.body, c.actuators);
  } catch (const runner::VehicleFactError& e) {
    throw std::runtime_error(where + ": <config key=\"" + e.key() + "\">: " + e.what());
  }
  const int k = c.actuation == "thrust_moments" ? runner::MisfitThrustMomentRole(facts) : -1;
  if (k >= 0) {
    throw std::runtime_error(where + ": <config key=\"actuators\">: actuator '" + c.actuators[k] +
                             "' is mapped as the " + runner::ThrustMomentRole(k) +
                             " but its gear is \"" + runner::GearText(facts.info[k].gear) +
                             "\" (the role needs gear entry " +
                             std::to_string(runner::ThrustMomentGearEntry(k)) + " alone non-zero)");
  }
  return facts;
}

}  // namespace

const std::vector<const char*>& VehicleAttributes() {
  static const std::vector<const char*> kNames = {"attitude",  "guidance",    "body",
                                                  "actuators", "plugin_path", "actuation"};
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
  c.actuation = get("actuation");
  if (!c.actuation.empty() && c.actuation != "rotors" && c.actuation != "thrust_moments") {
    throw std::runtime_error(c.where + ": <config key=\"actuation\">: \"" + c.actuation +
                             "\" is neither \"rotors\" nor \"thrust_moments\"");
  }
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
  const mjfPlugin& d = *attitude.descriptor;
  const runner::VehicleFacts facts = ReadFacts(m, s.config, d);
  s.body = facts.body;
  s.actuators = facts.actuators;
  s.actuator_info = facts.info;
  s.info.mass = facts.mass;
  std::memcpy(s.info.inertia, facts.inertia, sizeof(s.info.inertia));
  s.info.gravity = std::sqrt(mju_dot3(m->opt.gravity, m->opt.gravity));
  s.info.n_actuators = d.n_actuators;
  s.info.actuators = s.actuator_info.data();
  s.info.actuation =
      s.config.actuation == "thrust_moments" ? MJF_ACTUATION_THRUST_MOMENTS : MJF_ACTUATION_ROTORS;
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
