// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// libmjf_attitude.so and libmjf_guidance.so through the plugin ABI, as the runner uses them:
// dlopen, descriptors, create with a hand-made context (vehicle info from the model), compute.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "mjformation/attitude/pd_cascade.hpp"
#include "mjformation/attitude/pointmass_direct.hpp"
#include "mjformation/guidance/guidance.hpp"

namespace {

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

std::string Default(const mjfPlugin& plugin, const char* key) {
  for (int i = 0; i < plugin.n_attributes; ++i) {
    if (std::strcmp(plugin.attributes[i].key, key) == 0) return plugin.attributes[i].default_value;
  }
  ADD_FAILURE() << "no attribute " << key;
  return "";
}

mjfSetpoint NaNSetpoint() {
  mjfSetpoint sp;
  for (double* v : {sp.acc, sp.pos, sp.vel}) v[0] = v[1] = v[2] = kNaN;
  sp.yaw = sp.sliding[0] = sp.sliding[1] = kNaN;
  return sp;
}

TEST(AttitudePluginTest, ExportsBothPluginsWithTheirActuators) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  ASSERT_EQ(lib.size(), 2u);
  const mjfPlugin* cascade = lib.Get("pd_cascade");
  const mjfPlugin* pm = lib.Get("pointmass_direct");
  ASSERT_TRUE(cascade && pm);
  EXPECT_EQ(cascade->abi_version, MJF_ABI_VERSION);
  EXPECT_EQ(cascade->kind, MJF_KIND_ATTITUDE);
  ASSERT_EQ(cascade->n_actuators, 4);
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(std::string(cascade->actuators[k]), "rotor" + std::to_string(k));
  ASSERT_EQ(pm->n_actuators, 3);
  EXPECT_STREQ(pm->actuators[2], "fz");
  // Declared defaults are the pure classes' defaults.
  const mjf::attitude::PdCascade::Gains g;
  const std::map<std::string, double> expected = {
      {"tilt_max", g.tilt_max}, {"kp_att", g.kp_att}, {"kd_att", g.kd_att},
      {"kp_yaw", g.kp_yaw},     {"kd_yaw", g.kd_yaw}, {"kp_z", g.kp_z},
      {"ki_z", g.ki_z},         {"kd_z", g.kd_z},     {"imax_z", g.imax_z}};
  ASSERT_EQ(cascade->n_attributes, static_cast<int>(expected.size()));
  for (const auto& [key, value] : expected) {
    EXPECT_EQ(std::stod(Default(*cascade, key.c_str())), value) << key;
  }
  const mjf::attitude::PointMassDirect::Gains pg;
  EXPECT_EQ(std::stod(Default(*pm, "kp_z")), pg.kp_z);
  EXPECT_EQ(std::stod(Default(*pm, "kd_z")), pg.kd_z);
}

TEST(AttitudePluginTest, PdCascadeHoversOnTheModelsInfo) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const mjfPlugin* p = lib.Get("pd_cascade");
  ASSERT_TRUE(p);
  VehicleInfo info("quadrotor.xml", *p);
  EXPECT_NEAR(info.actuators[0].time_constant, 0.025, 1e-12);
  Context c(*p, {}, &info.vehicle, 1, nullptr);
  void* instance = p->create(&c.ctx);
  ASSERT_NE(instance, nullptr) << c.error;
  mjfVehicleState states[3] = {};
  for (auto& s : states) s.quat[0] = 1;
  states[1].pos[2] = 5;
  mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
  mjfSetpoint& sp = setpoints[1];
  sp.acc[0] = sp.acc[1] = sp.acc[2] = 0;
  sp.pos[2] = 5;
  sp.vel[2] = 0;
  sp.yaw = 0;
  double controls[4] = {kNaN, kNaN, kNaN, kNaN};
  mjfStepContext step{};
  step.timestep = 0.001;
  step.n_vehicles = 3;
  step.states = states;
  step.setpoints = setpoints;
  step.controls = controls;
  ASSERT_EQ(p->compute(instance, &step), 0);
  for (double u : controls) EXPECT_NEAR(u, 1.5 * 9.81 / 4, 1e-9);
  // A non-finite setpoint stops the run instead of producing garbage.
  sp.pos[2] = kNaN;
  EXPECT_NE(p->compute(instance, &step), 0);
  p->reset(instance);
  p->destroy(instance);
}

TEST(AttitudePluginTest, PointMassDirectGivesMassTimesCommand) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const mjfPlugin* p = lib.Get("pointmass_direct");
  ASSERT_TRUE(p);
  VehicleInfo info("pointmass.xml", *p);
  EXPECT_NEAR(info.vehicle.mass, 1, 1e-12);
  Context c(*p, {}, &info.vehicle, 0, nullptr);
  void* instance = p->create(&c.ctx);
  ASSERT_NE(instance, nullptr) << c.error;
  mjfVehicleState state{};
  state.quat[0] = 1;
  state.pos[2] = 2;
  mjfSetpoint sp = NaNSetpoint();
  sp.acc[0] = 0.3;
  sp.acc[1] = -0.4;
  sp.acc[2] = 0.1;
  sp.pos[2] = 2;
  sp.vel[2] = 0;
  sp.yaw = 0;
  double controls[3];
  mjfStepContext step{};
  step.timestep = 0.001;
  step.n_vehicles = 1;
  step.states = &state;
  step.setpoints = &sp;
  step.controls = controls;
  ASSERT_EQ(p->compute(instance, &step), 0);
  EXPECT_DOUBLE_EQ(controls[0], 0.3);
  EXPECT_DOUBLE_EQ(controls[1], -0.4);
  EXPECT_NEAR(controls[2], 9.81 + 0.1, 1e-12);
  p->destroy(instance);
}

TEST(AttitudePluginTest, BadAttributesAreRefusedByName) {
  Library lib(MJF_ATTITUDE_PLUGIN);
  const mjfPlugin* p = lib.Get("pd_cascade");
  ASSERT_TRUE(p);
  VehicleInfo info("quadrotor.xml", *p);
  const std::map<std::string, std::string> bad[] = {
      {{"kp_att", "abc"}}, {{"tilt_max", "2"}}, {{"kd_z", "-1"}}, {{"imax_z", "nan"}}};
  for (const auto& overrides : bad) {
    Context c(*p, overrides, &info.vehicle, 0, nullptr);
    EXPECT_EQ(p->create(&c.ctx), nullptr);
    EXPECT_NE(std::string(c.error).find(overrides.begin()->first), std::string::npos) << c.error;
  }
  // A vehicle whose rotors all sit on one line cannot roll: refused at create().
  VehicleInfo flat("quadrotor.xml", *p);
  for (auto& a : flat.actuators) a.site_pos[1] = 0;
  Context c(*p, {}, &flat.vehicle, 0, nullptr);
  EXPECT_EQ(p->create(&c.ctx), nullptr);
  EXPECT_NE(std::string(c.error).find("allocation"), std::string::npos) << c.error;
  // No vehicle info.
  Context none(*p, {}, nullptr, 0, nullptr);
  EXPECT_EQ(p->create(&none.ctx), nullptr);
  EXPECT_STRNE(none.error, "");
}

TEST(GuidancePluginTest, CircleWritesItsVehiclesSetpointOnly) {
  Library lib(MJF_GUIDANCE_PLUGIN);
  ASSERT_EQ(lib.size(), 7u);
  const mjfPlugin* p = lib.Get("circle");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->kind, MJF_KIND_GUIDANCE);
  Context c(*p, {{"center", "1 2"}, {"altitude", "4"}, {"yaw", "0.3"}}, nullptr, 0, nullptr);
  void* instance = p->create(&c.ctx);
  ASSERT_NE(instance, nullptr) << c.error;
  mjfVehicleState states[3] = {};
  states[0].pos[0] = 21;  // on the circle at t = 0, at rest
  states[0].pos[1] = 2;
  mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
  mjfStepContext step{};
  step.time = 0;
  step.timestep = 0.001;
  step.n_vehicles = 3;
  step.states = states;
  step.setpoints = setpoints;
  ASSERT_EQ(p->compute(instance, &step), 0);
  const mjfSetpoint& sp = setpoints[0];
  const double w = 0.157, r = 20;
  EXPECT_NEAR(sp.pos[0], 21, 1e-12);
  EXPECT_NEAR(sp.pos[1], 2, 1e-12);
  EXPECT_NEAR(sp.pos[2], 4, 1e-12);
  EXPECT_NEAR(sp.vel[1], r * w, 1e-12);
  // a = a_ref + kp (0) + kd (v_ref - 0) with kd = 2.
  EXPECT_NEAR(sp.acc[0], -r * w * w, 1e-12);
  EXPECT_NEAR(sp.acc[1], 2 * r * w, 1e-12);
  EXPECT_NEAR(sp.yaw, 0.3, 1e-12);
  EXPECT_TRUE(std::isnan(sp.sliding[0]) && std::isnan(sp.sliding[1]));
  EXPECT_TRUE(std::isnan(setpoints[1].acc[0]) && std::isnan(setpoints[2].pos[2]));
  p->destroy(instance);

  for (const auto& [key, value] :
       std::map<std::string, std::string>{{"radius", "-1"}, {"center", "1"}, {"omega", "fast"}}) {
    Context bad(*p, {{key, value}}, nullptr, 0, nullptr);
    EXPECT_EQ(p->create(&bad.ctx), nullptr);
    EXPECT_NE(std::string(bad.error).find(key), std::string::npos) << bad.error;
  }
}

TEST(GuidancePluginTest, HoverHoldsInitialPositionOrAttributes) {
  Library lib(MJF_GUIDANCE_PLUGIN);
  const mjfPlugin* p = lib.Get("hover");
  ASSERT_TRUE(p);
  const double initial[3] = {1, 2, 3};
  mjfVehicleState states[3] = {};
  mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
  mjfStepContext step{};
  step.n_vehicles = 3;
  step.states = states;
  step.setpoints = setpoints;
  {
    Context c(*p, {{"altitude", "7"}}, nullptr, 2, initial);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << c.error;
    states[2].vel[0] = 0.5;
    ASSERT_EQ(p->compute(instance, &step), 0);
    EXPECT_NEAR(setpoints[2].pos[0], 1, 1e-12);
    EXPECT_NEAR(setpoints[2].pos[2], 7, 1e-12);
    EXPECT_NEAR(setpoints[2].acc[0], 1 * (1 - 0) - 2 * 0.5, 1e-12);
    EXPECT_NEAR(setpoints[2].acc[1], 1 * 2, 1e-12);
    EXPECT_TRUE(std::isnan(setpoints[2].sliding[0]));
    p->destroy(instance);
  }
  {
    Context c(*p, {{"position", "4 5 6"}}, nullptr, 0, initial);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << c.error;
    ASSERT_EQ(p->compute(instance, &step), 0);
    EXPECT_NEAR(setpoints[0].pos[1], 5, 1e-12);
    EXPECT_NEAR(setpoints[0].pos[2], 6, 1e-12);
    p->destroy(instance);
  }
  for (const auto& [key, value] :
       std::map<std::string, std::string>{{"position", "1 2"}, {"kp", "-3"}, {"altitude", "x"}}) {
    Context bad(*p, {{key, value}}, nullptr, 0, initial);
    EXPECT_EQ(p->create(&bad.ctx), nullptr);
    EXPECT_NE(std::string(bad.error).find(key), std::string::npos) << bad.error;
  }
  Context no_start(*p, {}, nullptr, 0, nullptr);
  EXPECT_EQ(p->create(&no_start.ctx), nullptr);
  EXPECT_NE(std::string(no_start.error).find("position"), std::string::npos) << no_start.error;
}

}  // namespace

// The maneuvering leaders through the ABI: defaults create and command inside the bounds; bad
// input is refused at create() with the attribute's name (the host adds FILE:LINE: [leader]).
TEST(GuidancePluginTest, ManeuveringLeadersCreateComputeAndRefuseBadInput) {
  Library lib(MJF_GUIDANCE_PLUGIN);
  const std::string csv = ::testing::TempDir() + "/leader_path.csv";
  {
    std::FILE* f = std::fopen(csv.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("t,x,y\n0,0,0\n5,3,1\n10,6,0\n", f);
    std::fclose(f);
  }
  for (const char* name : {"random_accel", "bang_bang", "lemniscate", "waypoints", "trajectory"}) {
    const mjfPlugin* p = lib.Get(name);
    ASSERT_TRUE(p) << name;
    EXPECT_EQ(p->kind, MJF_KIND_GUIDANCE);
    std::map<std::string, std::string> attributes = {{"a_min", "-0.5"}, {"a_max", "0.7"}};
    if (std::string(name) == "trajectory") attributes["file"] = csv;
    if (std::string(name) == "lemniscate") attributes["omega"] = "0.1";  // 2 A w^2 = 0.4
    if (std::string(name) == "waypoints") attributes["speed"] = "1";
    Context c(*p, attributes, nullptr, 0, nullptr);
    void* instance = p->create(&c.ctx);
    ASSERT_NE(instance, nullptr) << name << ": " << c.error;
    mjfVehicleState states[3] = {};
    states[0].pos[0] = 3;
    states[0].vel[1] = -2;
    mjfSetpoint setpoints[3] = {NaNSetpoint(), NaNSetpoint(), NaNSetpoint()};
    char error[128] = {0};
    mjfStepContext step{};
    step.timestep = 0.001;
    step.n_vehicles = 3;
    step.states = states;
    step.setpoints = setpoints;
    step.error = error;
    step.error_size = sizeof(error);
    for (int k = 0; k < 3000; ++k) {
      step.time = k * 0.001;
      step.step = k;
      ASSERT_EQ(p->compute(instance, &step), 0) << name << ": " << error;
      for (int i = 0; i < 2; ++i) {
        ASSERT_GE(setpoints[0].acc[i], -0.5) << name;
        ASSERT_LE(setpoints[0].acc[i], 0.7) << name;
      }
    }
    EXPECT_TRUE(std::isnan(setpoints[1].acc[0]));
    if (p->reset) p->reset(instance);
    p->destroy(instance);

    Context equal(*p, {{"a_min", "1"}, {"a_max", "1"}, {"file", csv}}, nullptr, 0, nullptr);
    EXPECT_EQ(p->create(&equal.ctx), nullptr) << name;
    EXPECT_NE(std::string(equal.error).find("a_min"), std::string::npos) << equal.error;
  }
  const std::vector<std::tuple<std::string, std::string, std::string>> bad = {
      {"bang_bang", "dwell", "0 1"},
      {"bang_bang", "dwell", "-1 1"},
      {"random_accel", "seed", "-3"},
      {"random_accel", "seed", "1.5"},
      {"random_accel", "area", "0 0 -1 5"},
      {"waypoints", "points", "0 0 1 0 1 1"},  // too close at 2 m/s
      {"waypoints", "points", "0 0 1"},
      {"trajectory", "file", "/nonexistent.csv"},
      {"trajectory", "file", ""},
  };
  for (const auto& [name, key, value] : bad) {
    Context c(*lib.Get(name), {{key, value}}, nullptr, 0, nullptr);
    EXPECT_EQ(lib.Get(name)->create(&c.ctx), nullptr) << name << " " << key << " = " << value;
    EXPECT_NE(std::string(c.error).find("'" + key + "'"), std::string::npos) << c.error;
  }
}
