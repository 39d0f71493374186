// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the plugin-family tests share: a family dlopen()ed like the runner does, the vehicle info
// the host gives an attitude plugin, and a create context with the declared defaults.
#ifndef MJFORMATION_TESTS_PLUGINS_SUPPORT_PLUGIN_LOADER_HPP_
#define MJFORMATION_TESTS_PLUGINS_SUPPORT_PLUGIN_LOADER_HPP_

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace mjf::test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class Library {
 public:
  explicit Library(const char* path) {
    handle_ = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!handle_) {
      ADD_FAILURE() << dlerror();
      return;
    }
    auto entry = reinterpret_cast<mjfEntryFn>(dlsym(handle_, MJF_ENTRY_SYMBOL));
    if (!entry) {
      ADD_FAILURE() << path << ": no " << MJF_ENTRY_SYMBOL;
      return;
    }
    int count = 0;
    const mjfPlugin* const* plugins = entry(&count);
    for (int i = 0; i < count; ++i) plugins_[plugins[i]->name] = plugins[i];
  }
  ~Library() {
    if (handle_) dlclose(handle_);
  }
  const mjfPlugin* Get(const std::string& name) const {
    auto it = plugins_.find(name);
    return it == plugins_.end() ? nullptr : it->second;
  }
  size_t size() const { return plugins_.size(); }

 private:
  void* handle_ = nullptr;
  std::map<std::string, const mjfPlugin*> plugins_;
};

// Vehicle info of a vehicle file, filled as runner/src/simulation.cc does.
struct VehicleInfo {
  explicit VehicleInfo(const std::string& file, const mjfPlugin& plugin) {
    char error[1024] = {0};
    mjModel* m =
        mj_loadXML((std::string(MJF_MJCF_DIR) + "/" + file).c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
    mjData* d = mj_makeData(m);
    mj_forward(m, d);
    const int body = mj_name2id(m, mjOBJ_BODY, "vehicle");
    for (int k = 0; k < plugin.n_actuators; ++k) {
      const int a = mj_name2id(m, mjOBJ_ACTUATOR, plugin.actuators[k]);
      EXPECT_GE(a, 0) << plugin.actuators[k];
      mjfActuatorInfo info{};
      std::memcpy(info.gear, m->actuator_gear + 6 * a, sizeof(info.gear));
      info.ctrl_min = m->actuator_ctrllimited[a] ? m->actuator_ctrlrange[2 * a] : -INFINITY;
      info.ctrl_max = m->actuator_ctrllimited[a] ? m->actuator_ctrlrange[2 * a + 1] : INFINITY;
      info.time_constant =
          m->actuator_dyntype[a] == mjDYN_FILTER ? m->actuator_dynprm[mjNDYN * a] : 0;
      if (m->actuator_trntype[a] == mjTRN_SITE) {
        const int site = m->actuator_trnid[2 * a];
        double rel[3];
        mju_sub3(rel, d->site_xpos + 3 * site, d->xipos + 3 * body);
        mju_mulMatTVec(info.site_pos, d->xmat + 9 * body, rel, 3, 3);
      }
      actuators.push_back(info);
    }
    vehicle.mass = m->body_subtreemass[body];
    std::memcpy(vehicle.inertia, m->body_inertia + 3 * body, sizeof(vehicle.inertia));
    vehicle.gravity = mju_norm3(m->opt.gravity);
    vehicle.n_actuators = plugin.n_actuators;
    vehicle.actuators = actuators.data();
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  std::vector<mjfActuatorInfo> actuators;
  mjfVehicleInfo vehicle{};
};

// A create context with the declared defaults, some overridden.
class Context {
 public:
  Context(const mjfPlugin& plugin, const std::map<std::string, std::string>& overrides,
          const mjfVehicleInfo* info, int vehicle, const double* initial_pos) {
    for (int i = 0; i < plugin.n_attributes; ++i) {
      const mjfAttribute& a = plugin.attributes[i];
      keys_.push_back(a.key);
      auto it = overrides.find(a.key);
      values_.push_back(it != overrides.end() ? it->second : a.default_value);
    }
    for (auto& k : keys_) key_ptrs_.push_back(k.c_str());
    for (auto& v : values_) value_ptrs_.push_back(v.c_str());
    ctx.n_attributes = plugin.n_attributes;
    ctx.keys = key_ptrs_.data();
    ctx.values = value_ptrs_.data();
    ctx.timestep = 0.001;
    ctx.vehicle = vehicle;
    ctx.n_vehicles = 3;
    ctx.vehicle_info = info;
    ctx.initial_pos = initial_pos;
    ctx.error = error;
    ctx.error_size = sizeof(error);
  }
  mjfCreateContext ctx{};
  char error[256] = {0};

 private:
  std::vector<std::string> keys_, values_;
  std::vector<const char*> key_ptrs_, value_ptrs_;
};

inline std::string Default(const mjfPlugin& plugin, const char* key) {
  for (int i = 0; i < plugin.n_attributes; ++i) {
    if (std::strcmp(plugin.attributes[i].key, key) == 0) return plugin.attributes[i].default_value;
  }
  ADD_FAILURE() << "no attribute " << key;
  return "";
}

inline mjfSetpoint NaNSetpoint() {
  mjfSetpoint sp;
  for (double* v : {sp.acc, sp.pos, sp.vel}) v[0] = v[1] = v[2] = kNaN;
  sp.yaw = sp.sliding[0] = sp.sliding[1] = kNaN;
  return sp;
}

}  // namespace mjf::test

#endif  // MJFORMATION_TESTS_PLUGINS_SUPPORT_PLUGIN_LOADER_HPP_
