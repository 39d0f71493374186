// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "one_driver.hpp"

#include <mujoco/mjplugin.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>

#include "attach_names.hpp"
#include "attitude_plugin.hpp"
#include "native_instance.hpp"
#include "swarm_plugin.hpp"

namespace mjf::native {
namespace {

bool IsSwarm(const mjModel* m, int instance) {
  const mjpPlugin* kind = mjp_getPluginAtSlot(m->plugin[instance]);
  return kind && std::string(kind->name) == SwarmPlugin::kName;
}

// What an instance flies, by the names in `m` (after any attach): a swarm its vehicles' bodies,
// an attitude instance its body and actuators.
struct Driven {
  bool swarm = false;
  std::vector<std::string> bodies, actuators;
};

// Null for an instance of a plugin other than ours.
std::unique_ptr<Driven> DrivenBy(const mjModel* m, int instance) {
  const mjpPlugin* kind = mjp_getPluginAtSlot(m->plugin[instance]);
  auto driven = std::make_unique<Driven>();
  if (IsSwarm(m, instance)) {
    const runner::ExperimentConfig config = SwarmPlugin::Config(m, instance);
    const runner::SceneNames names = SwarmPlugin::Names(m, instance, config);
    driven->swarm = true;
    for (const std::string& body : SwarmPlugin::Bodies(config.followers)) {
      driven->bodies.push_back(names(body));
    }
  } else if (kind && std::string(kind->name) == AttitudePlugin::kName) {
    const VehicleHostConfig c = AttitudePlugin::Config(m, instance);
    driven->bodies = {c.body};
    driven->actuators = c.actuators;
  } else {
    return nullptr;
  }
  return driven;
}

// A swarm's affixes without its configuration (as many vehicles as bodies reference it), so that
// two swarms on one set of vehicles are named as such before either's configuration is read;
// nullopt when they do not resolve (SwarmPlugin::Names then words the refusal).
std::optional<runner::SceneNames> SwarmAffixes(const mjModel* m, int instance) {
  int referencing = 0;
  for (int b = 1; b < m->nbody; ++b) referencing += m->body_plugin[b] == instance;
  try {
    return InstanceNames(m, instance, SwarmPlugin::Bodies(std::max(referencing, 1) - 1), "");
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

std::runtime_error SecondSwarm(const mjModel* m, int instance, int other, const std::string& body) {
  return std::runtime_error(
      InstanceWhere(SwarmPlugin::kName, m, instance) + ": a second swarm instance ('" +
      InstanceName(m, other) + "' is the other) flies the same vehicles ('" + body +
      "'); remove one of them, or attach each copy under a prefix " + "of its own");
}

// Two swarm instances whose vehicles carry the same affixes fly the same vehicles.
void RefuseSecondSwarm(const mjModel* m, int instance) {
  const std::optional<runner::SceneNames> mine = SwarmAffixes(m, instance);
  for (int other = 0; mine && other < m->nplugin; ++other) {
    if (other == instance || !IsSwarm(m, other)) continue;
    const std::optional<runner::SceneNames> theirs = SwarmAffixes(m, other);
    if (!theirs || theirs->prefix != mine->prefix || theirs->suffix != mine->suffix) continue;
    throw SecondSwarm(m, instance, other, (*mine)(SwarmPlugin::Bodies(0)[0]));
  }
}

std::string Shared(const std::vector<std::string>& mine, const std::vector<std::string>& theirs) {
  for (const std::string& name : mine) {
    if (std::find(theirs.begin(), theirs.end(), name) != theirs.end()) return name;
  }
  return "";
}

}  // namespace

// No vehicle driven twice, refused while the model compiles: no two swarms fly the same
// vehicles (two attached copies under their own prefixes fly their own), no actuator is named by
// two attitude instances and no body is flown by two instances (the later instance's controls
// would silently replace the earlier's).
void RefuseDrivingTwice(const char* plugin, const mjModel* m, int instance) {
  if (IsSwarm(m, instance)) RefuseSecondSwarm(m, instance);
  const std::unique_ptr<Driven> mine = DrivenBy(m, instance);
  for (int other = 0; mine && other < m->nplugin; ++other) {
    const std::unique_ptr<Driven> theirs = other == instance ? nullptr : DrivenBy(m, other);
    if (!theirs) continue;
    const std::string actuator = Shared(mine->actuators, theirs->actuators);
    if (!actuator.empty()) {
      throw std::runtime_error(InstanceWhere(plugin, m, instance) +
                               ": <config key=\"actuators\">: '" + actuator +
                               "' is driven by instance '" + InstanceName(m, other) +
                               "' too; an actuator takes one instance's controls");
    }
    const std::string body = Shared(mine->bodies, theirs->bodies);
    if (body.empty()) continue;
    if (mine->swarm && theirs->swarm) throw SecondSwarm(m, instance, other, body);
    throw std::runtime_error(InstanceWhere(plugin, m, instance) + ": body '" + body +
                             "' is flown by instance '" + InstanceName(m, other) +
                             "' too; a vehicle takes one instance's controls");
  }
}

}  // namespace mjf::native
