// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Plugin-level test: dlopen libmjf_formation.so as the runner does, fetch the descriptors
// through mjf_plugin_entry, create with a context, run compute on a small point-mass swarm.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <mjformation/plugin.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mjformation/formation/metrics.hpp>
#include <mjformation/formation/shape.hpp>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSentinel = 123.5;

class FormationPluginTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    handle_ = dlopen(MJF_FORMATION_PLUGIN_PATH, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(handle_, nullptr) << dlerror();
    auto entry = reinterpret_cast<mjfEntryFn>(dlsym(handle_, MJF_ENTRY_SYMBOL));
    ASSERT_NE(entry, nullptr) << dlerror();
    int count = 0;
    const mjfPlugin* const* plugins = entry(&count);
    for (int k = 0; k < count; ++k) plugins_[plugins[k]->name] = plugins[k];
  }
  static void TearDownTestSuite() {
    if (handle_) dlclose(handle_);
    handle_ = nullptr;
  }

  const mjfPlugin* Plugin(const std::string& name) {
    EXPECT_EQ(plugins_.count(name), 1u) << name;
    return plugins_.at(name);
  }

  // Paper graph: 1 hears the leader; chain 1 -> ... -> 6 with 1 -> 3, 3 -> 5, 6 -> 4.
  std::vector<double> leader_weight_ = {1, 0, 0, 0, 0, 0};
  std::vector<int> from_ = {0, 1, 2, 3, 4, 0, 2, 5};
  std::vector<int> to_ = {1, 2, 3, 4, 5, 2, 4, 3};
  std::vector<double> weight_ = std::vector<double>(8, 1.0);
  std::unique_ptr<mjf::formation::Shape> shape_ =
      mjf::formation::MakeCircleShape(6, 10.0, 0.314, 0.0, kPi / 3);

  // Creates `plugin` with its declared defaults overridden by `overrides`.
  void* Create(const mjfPlugin* plugin, const std::map<std::string, std::string>& overrides,
               std::string* error, double timestep = 0.01, bool spanning_tree = true,
               const mjfNeighbourhood* neighbourhood = nullptr) {
    keys_.clear();
    values_.clear();
    for (int k = 0; k < plugin->n_attributes; ++k) {
      const mjfAttribute& a = plugin->attributes[k];
      keys_.push_back(a.key);
      auto it = overrides.find(a.key);
      values_.push_back(it != overrides.end() ? it->second.c_str() : a.default_value);
    }
    for (const auto& [key, value] : overrides) {
      bool declared = false;
      for (const char* k : keys_) declared |= key == k;
      EXPECT_TRUE(declared) << plugin->name << " does not declare '" << key << "'";
    }
    std::vector<double> leader = leader_weight_;
    if (!spanning_tree) leader[0] = 0.0;
    graph_leader_ = leader;
    graph_ = {6, graph_leader_.data(), 8, from_.data(), to_.data(), weight_.data()};
    abi_shape_ = mjf::formation::ToAbi(*shape_);
    char buffer[512] = "";
    mjfCreateContext ctx{};
    ctx.n_attributes = static_cast<int>(keys_.size());
    ctx.keys = keys_.data();
    ctx.values = values_.data();
    ctx.timestep = timestep;
    ctx.vehicle = -1;
    ctx.n_vehicles = shape_->num_followers() + 1;
    ctx.graph = neighbourhood ? nullptr : &graph_;  // a per-agent instance gets its row only
    ctx.neighbourhood = neighbourhood;
    ctx.shape = &abi_shape_;
    ctx.error = buffer;
    ctx.error_size = sizeof(buffer);
    void* instance = plugin->create(&ctx);
    *error = buffer;
    return instance;
  }

  struct RunResult {
    double sigma_initial = 0, sigma_final = 0;
    bool untouched = true, finite = true, slots_ok = true;
    std::vector<std::vector<double>> acc_x;  // per step, follower 1..6
  };

  // Point masses following setpoints[i].acc (Euler, timestep h), leader on the paper's circle.
  RunResult Run(const mjfPlugin* plugin, void* instance, int steps, double h = 0.01) {
    RunResult result;
    std::vector<mjfVehicleState> states(7);
    std::vector<mjfSetpoint> setpoints(7);
    std::vector<double> f(36);
    for (int i = 1; i <= 6; ++i) {
      states[i] = mjfVehicleState{};
      states[i].pos[0] = 2.0 * i - 6.0;  // near the origin, as in the paper's Fig. 27
      states[i].pos[1] = -1.0;
      states[i].pos[2] = 5.0;
    }
    std::vector<double> leader_pv(4), follower_pv(24);
    for (int k = 0; k <= steps; ++k) {
      const double t = k * h;
      mjfVehicleState& leader = states[0];
      leader.pos[0] = 20 * std::cos(0.157 * t);
      leader.pos[1] = 20 * std::sin(0.157 * t);
      leader.vel[0] = -20 * 0.157 * std::sin(0.157 * t);
      leader.vel[1] = 20 * 0.157 * std::cos(0.157 * t);
      for (auto& sp : setpoints) {
        sp.acc[2] = sp.pos[2] = sp.vel[2] = sp.yaw = kSentinel;
        sp.sliding[0] = sp.sliding[1] = std::nan("");
      }
      mjfStepContext ctx{};
      ctx.time = t;
      ctx.step = k;
      ctx.timestep = h;
      ctx.n_vehicles = 7;
      ctx.states = states.data();
      ctx.setpoints = setpoints.data();
      EXPECT_EQ(plugin->compute(instance, &ctx), 0);
      shape_->Evaluate(t, f.data());
      for (int c = 0; c < 2; ++c) {
        leader_pv[c] = leader.pos[c];
        leader_pv[2 + c] = leader.vel[c];
      }
      std::vector<double> row;
      for (int i = 1; i <= 6; ++i) {
        mjfSetpoint& sp = setpoints[i];
        result.untouched &= sp.acc[2] == kSentinel && sp.pos[2] == kSentinel &&
                            sp.vel[2] == kSentinel && sp.yaw == kSentinel;
        result.finite &= std::isfinite(sp.acc[0]) && std::isfinite(sp.acc[1]);
        for (int c = 0; c < 2; ++c) {
          result.slots_ok &= std::abs(sp.pos[c] - leader.pos[c] - f[6 * (i - 1) + c]) < 1e-9 &&
                             std::abs(sp.vel[c] - leader.vel[c] - f[6 * (i - 1) + 2 + c]) < 1e-9;
          follower_pv[4 * (i - 1) + c] = states[i].pos[c];
          follower_pv[4 * (i - 1) + 2 + c] = states[i].vel[c];
        }
        row.push_back(sp.acc[0]);
      }
      result.acc_x.push_back(row);
      const double sigma =
          mjf::formation::FormationError(6, follower_pv.data(), leader_pv.data(), f.data());
      if (k == 0) result.sigma_initial = sigma;
      result.sigma_final = sigma;
      for (int i = 1; i <= 6; ++i) {
        for (int c = 0; c < 2; ++c) {
          states[i].pos[c] += h * states[i].vel[c];
          states[i].vel[c] += h * setpoints[i].acc[c];
        }
      }
    }
    return result;
  }

  static std::map<std::string, double> Report(const mjfPlugin* plugin, void* instance) {
    std::map<std::string, double> values;
    if (plugin->report) {
      plugin->report(
          instance,
          [](void* user, const char* key, double value) {
            (*static_cast<std::map<std::string, double>*>(user))[key] = value;
          },
          &values);
    }
    return values;
  }

  static void* handle_;
  static std::map<std::string, const mjfPlugin*> plugins_;
  std::vector<const char*> keys_, values_;
  std::vector<double> graph_leader_;
  mjfGraph graph_{};
  mjfShape abi_shape_{};
};

void* FormationPluginTest::handle_ = nullptr;
std::map<std::string, const mjfPlugin*> FormationPluginTest::plugins_;

TEST_F(FormationPluginTest,
       ExportsThreeFormationPluginsFiveFromTheLiteratureAndTheirPerAgentVersions) {
  ASSERT_EQ(plugins_.size(), 16u);
  for (const char* name :
       {"smc_continuous", "smc_discrete", "consensus_linear", "smc_continuous_agent",
        "smc_discrete_agent", "consensus_linear_agent", "vs_tracking", "super_twisting",
        "adaptive_tracking", "observer_tracking", "terminal_smc", "vs_tracking_agent",
        "super_twisting_agent", "adaptive_tracking_agent", "observer_tracking_agent",
        "terminal_smc_agent"}) {
    const mjfPlugin* p = Plugin(name);
    EXPECT_EQ(p->abi_version, MJF_ABI_VERSION);
    EXPECT_EQ(p->kind, std::string(name).find("_agent") == std::string::npos
                           ? MJF_KIND_FORMATION
                           : MJF_KIND_FORMATION_AGENT);
    EXPECT_NE(p->create, nullptr);
    EXPECT_NE(p->compute, nullptr);
    EXPECT_NE(p->destroy, nullptr);
  }
}

// Each law from the literature, with its default (untuned) gains, through the ABI on the
// point-mass swarm: writes only x-y commands and the slots, finite commands and sliding values,
// brings the formation error down, and after reset() repeats the same commands (its state, e.g.
// an adaptive gain or an estimate, goes back to the start).
TEST_F(FormationPluginTest, LawsFromTheLiteratureFlyAndResetToTheirStart) {
  for (const char* name : {"vs_tracking", "super_twisting", "adaptive_tracking",
                           "observer_tracking", "terminal_smc"}) {
    SCOPED_TRACE(name);
    const mjfPlugin* p = Plugin(name);
    std::string error;
    void* instance = Create(p, {}, &error, 0.01);
    ASSERT_NE(instance, nullptr) << error;
    const RunResult first = Run(p, instance, 3000);
    EXPECT_TRUE(first.untouched);
    EXPECT_TRUE(first.finite);
    EXPECT_TRUE(first.slots_ok);
    EXPECT_LT(first.sigma_final, 0.5 * first.sigma_initial);
    p->reset(instance);
    const RunResult again = Run(p, instance, 3000);
    EXPECT_EQ(again.acc_x, first.acc_x);
    p->destroy(instance);
  }
}

// A bad gain is refused at create() with a reason naming the attribute.
TEST_F(FormationPluginTest, LawsFromTheLiteratureRefuseBadGainsNamingTheKey) {
  const std::map<std::string, std::pair<std::string, std::string>> bad = {
      {"vs_tracking", {"beta", "-1"}},
      {"super_twisting", {"lambda", "0"}},
      {"adaptive_tracking", {"phi", "-1"}},
      {"observer_tracking", {"gamma", "0"}},
      {"terminal_smc", {"p", "4"}}};
  // The per-agent versions read the same attributes and refuse the same values.
  const int neighbours[1] = {5};
  const double weights[1] = {1.0};
  const mjfNeighbourhood hood{0, 6, 1.0, 1, neighbours, weights};
  for (const auto& [law, key_value] : bad) {
    for (const std::string& name : {law, law + "_agent"}) {
      const bool agent = name != law;
      std::string error;
      void* instance = Create(Plugin(name), {{key_value.first, key_value.second}}, &error, 0.01,
                              true, agent ? &hood : nullptr);
      EXPECT_EQ(instance, nullptr) << name;
      EXPECT_NE(error.find("'" + key_value.first + "'"), std::string::npos)
          << name << ": " << error;
    }
  }
}

TEST_F(FormationPluginTest, DiscreteHoldsBetweenSamplesAndConverges) {
  const mjfPlugin* p = Plugin("smc_discrete");
  std::string error;
  void* instance = Create(p, {{"period", "0.05"}}, &error);
  ASSERT_NE(instance, nullptr) << error;
  const RunResult r = Run(p, instance, 4000);
  EXPECT_TRUE(r.untouched);
  EXPECT_TRUE(r.finite);
  EXPECT_TRUE(r.slots_ok);
  for (size_t k = 0; k + 5 < r.acc_x.size(); k += 5) {
    for (int m = 1; m < 5; ++m) EXPECT_EQ(r.acc_x[k + m], r.acc_x[k]) << "step " << k + m;
  }
  EXPECT_NE(r.acc_x[5], r.acc_x[0]);
  EXPECT_LT(r.sigma_final, 0.1 * r.sigma_initial);
  const auto report = Report(p, instance);
  EXPECT_GT(report.at("delta"), 0.0);
  EXPECT_GT(report.at("error_bound"), 0.0);
  EXPECT_GT(report.at("norm_inv_lh"), 0.0);
  EXPECT_EQ(report.at("steps_per_sample"), 5.0);
  p->destroy(instance);
}

TEST_F(FormationPluginTest, ContinuousSwitchingExponentialConverges) {
  const mjfPlugin* p = Plugin("smc_continuous");
  std::string error;
  void* instance = Create(p, {{"compensation", "switching"}, {"reaching", "exponential"}}, &error);
  ASSERT_NE(instance, nullptr) << error;
  const RunResult r = Run(p, instance, 3000);
  EXPECT_TRUE(r.untouched);
  EXPECT_TRUE(r.finite);
  EXPECT_TRUE(r.slots_ok);
  EXPECT_LT(r.sigma_final, 0.05 * r.sigma_initial);
  const auto report = Report(p, instance);
  EXPECT_GT(report.at("reaching_time_bound"), 0.0);
  p->reset(instance);
  p->destroy(instance);
}

TEST_F(FormationPluginTest, ConsensusConvergesWithDefaults) {
  const mjfPlugin* p = Plugin("consensus_linear");
  std::string error;
  void* instance = Create(p, {}, &error);
  ASSERT_NE(instance, nullptr) << error;
  const RunResult r = Run(p, instance, 4000);
  EXPECT_TRUE(r.untouched);
  EXPECT_TRUE(r.finite);
  EXPECT_LT(r.sigma_final, 0.2 * r.sigma_initial);
  p->destroy(instance);
}

// The swarm-level laws share one compute: a step that does not carry the swarm is refused with
// the same message by each, and a law without a sliding variable leaves sliding NaN.
TEST_F(FormationPluginTest, SwarmLawsRefuseAStepWithoutTheSwarm) {
  for (const char* name : {"smc_continuous", "smc_discrete", "consensus_linear"}) {
    SCOPED_TRACE(name);
    const mjfPlugin* p = Plugin(name);
    ASSERT_NE(p->reset, nullptr);
    std::string create_error;
    void* instance = Create(p, {}, &create_error);
    ASSERT_NE(instance, nullptr) << create_error;
    std::vector<mjfVehicleState> states(7);
    std::vector<mjfSetpoint> setpoints(7);
    char error[128] = "";
    mjfStepContext ctx{};
    ctx.timestep = 0.01;
    ctx.n_vehicles = 6;  // one follower short
    ctx.states = states.data();
    ctx.setpoints = setpoints.data();
    ctx.error = error;
    ctx.error_size = sizeof(error);
    EXPECT_EQ(p->compute(instance, &ctx), 1);
    EXPECT_STREQ(error, "the step does not carry 1 + n_followers vehicle states and setpoints");
    ctx.n_vehicles = 7;
    for (auto& sp : setpoints) sp.sliding[0] = sp.sliding[1] = std::nan("");
    ASSERT_EQ(p->compute(instance, &ctx), 0) << error;
    EXPECT_EQ(std::isnan(setpoints[1].sliding[0]), std::string(name) == "consensus_linear");
    p->reset(instance);
    p->destroy(instance);
  }
}

// Reset forgets the held sample: the next step samples again, whatever its step number.
TEST_F(FormationPluginTest, DiscreteSamplesAgainAfterReset) {
  const mjfPlugin* p = Plugin("smc_discrete");
  std::string error;
  void* instance = Create(p, {{"period", "0.05"}}, &error);  // 5 steps of 0.01 s
  ASSERT_NE(instance, nullptr) << error;
  std::vector<mjfVehicleState> states(7);
  for (int i = 1; i <= 6; ++i) states[i].pos[0] = i;
  std::vector<mjfSetpoint> setpoints(7);
  mjfStepContext ctx{};
  ctx.timestep = 0.01;
  ctx.n_vehicles = 7;
  ctx.states = states.data();
  ctx.setpoints = setpoints.data();
  ASSERT_EQ(p->compute(instance, &ctx), 0);  // step 0: the first sample
  const double first = setpoints[1].acc[0];
  states[1].pos[0] += 3.0;  // moved: a new sample would command something else
  ctx.step = 2;
  ctx.time = 0.02;
  ASSERT_EQ(p->compute(instance, &ctx), 0);
  EXPECT_EQ(setpoints[1].acc[0], first);  // held between samples
  p->reset(instance);
  ASSERT_EQ(p->compute(instance, &ctx), 0);
  EXPECT_NE(setpoints[1].acc[0], first);  // sampled at step 2, the first after reset
  p->destroy(instance);
}

TEST_F(FormationPluginTest, BadConfigurationGivesNullAndMessage) {
  struct Bad {
    const char* plugin;
    std::map<std::string, std::string> overrides;
    const char* fragment;
  };
  const Bad cases[] = {
      {"smc_continuous", {{"rho", "-1"}}, "'rho'"},
      {"smc_continuous", {{"k", "3"}}, "'k'"},
      {"smc_continuous", {{"k", "3 0"}}, "k1 > 0 and k2 > 0"},
      {"smc_continuous", {{"compensation", "upper"}}, "'compensation'"},
      {"smc_continuous", {{"sign", "sat"}, {"boundary_layer", "0"}}, "'boundary_layer'"},
      {"smc_continuous", {{"u_min", "abc"}}, "'u_min'"},
      {"smc_discrete", {{"period", "0.033"}}, "not an integer multiple"},
      {"smc_discrete", {{"q", "30"}}, "1 - q*T > 0"},
      {"smc_discrete", {{"eps", "0"}}, "'eps'"},
      {"smc_discrete", {{"u_min", "2"}}, "'u_min' with 'u_max'"},
      {"consensus_linear", {{"kv", "0"}}, "'kv'"},
      {"smc_discrete", {{"accel_limit", "0"}}, "'accel_limit': the acceleration bound must be > 0"},
      {"smc_discrete", {{"accel_limit", "-2"}}, "'accel_limit'"},
      {"smc_discrete", {{"accel_limit", "nan"}}, "'accel_limit'"},
      {"smc_discrete", {{"accel_limit", "inf"}}, "'accel_limit'"},
      {"smc_discrete", {{"accel_limit", "fast"}}, "'accel_limit'"},
      {"smc_discrete", {{"accel_limit", "1.2"}}, "does not exceed the leader's acceleration bound"},
      {"smc_discrete", {{"accel_limit", "vehicle"}}, "must be resolved by the host"},
      {"smc_discrete", {{"reach_accel", "-1"}}, "'reach_accel'"},
  };
  for (const Bad& bad : cases) {
    std::string error;
    void* instance = Create(Plugin(bad.plugin), bad.overrides, &error);
    EXPECT_EQ(instance, nullptr) << bad.plugin << " " << bad.fragment;
    EXPECT_NE(error.find(bad.fragment), std::string::npos)
        << bad.plugin << ": '" << error << "' lacks '" << bad.fragment << "'";
  }
  for (const char* name : {"smc_continuous", "smc_discrete", "consensus_linear"}) {
    std::string error;
    EXPECT_EQ(Create(Plugin(name), {}, &error, 0.01, /*spanning_tree=*/false), nullptr);
    EXPECT_NE(error.find("Assumption 2"), std::string::npos) << error;
  }
}

}  // namespace

// Per-agent cost linear in N: an instance evaluates the desired formation only for itself and
// its in-neighbours, one follower at a time (mjfShape.evaluate_one), never the whole swarm
// (evaluate), so its cost per step does not grow with the number of followers. A counting shape
// of 1000 followers records every call.
class CountingShape : public mjf::formation::Shape {
 public:
  explicit CountingShape(std::unique_ptr<mjf::formation::Shape> shape) : shape_(std::move(shape)) {}
  int num_followers() const override { return shape_->num_followers(); }
  void Evaluate(double t, double* out) const override {
    ++whole;
    shape_->Evaluate(t, out);
  }
  void EvaluateOne(double t, int i, double* out) const override {
    ++single[i];
    shape_->EvaluateOne(t, i, out);
  }
  mutable long whole = 0;              // Evaluate() calls: O(N) each
  mutable std::map<int, long> single;  // EvaluateOne() calls per follower

 private:
  std::unique_ptr<mjf::formation::Shape> shape_;
};

TEST_F(FormationPluginTest, PerAgentInstancesEvaluateOnlyThemselvesAndTheirNeighbours) {
  for (const char* name : {"smc_discrete_agent", "smc_continuous_agent", "consensus_linear_agent",
                           "vs_tracking_agent", "super_twisting_agent", "adaptive_tracking_agent",
                           "observer_tracking_agent", "terminal_smc_agent"}) {
    auto counting = std::make_unique<CountingShape>(
        mjf::formation::MakeCircleShape(1000, 10.0, 0.314, 0.0, 2 * kPi / 1000));
    const CountingShape& counter = *counting;
    shape_ = std::move(counting);
    // Follower 500 of a ring hears follower 499 only.
    const int neighbours[1] = {499};
    const double weights[1] = {1.0};
    const mjfNeighbourhood hood{500, 1000, 0.0, 1, neighbours, weights};
    const mjfPlugin* plugin = Plugin(name);
    std::string error;
    void* instance = Create(plugin, {}, &error, 0.01, true, &hood);
    ASSERT_NE(instance, nullptr) << error;
    mjfVehicleState self{};
    mjfSetpoint setpoint{};
    mjfMessage neighbour{};
    neighbour.sender = 500;  // vehicle index of follower 499
    mjfMessage outgoing{};
    mjfAgentInput input{};
    input.follower = 500;
    input.self = &self;
    input.n_messages = 1;
    input.messages = &neighbour;
    input.n_rounds = 1;
    input.outgoing = &outgoing;
    char reason[256] = "";
    mjfStepContext step{};
    step.timestep = 0.01;
    step.n_vehicles = 1001;
    step.setpoints = &setpoint;
    step.agent = &input;
    step.error = reason;
    step.error_size = sizeof(reason);
    constexpr int kSteps = 100;
    for (int s = 0; s < kSteps; ++s) {
      step.step = s;
      step.time = 0.01 * s;
      neighbour.send_time = step.time;
      ASSERT_EQ(plugin->compute(instance, &step), 0) << name << ": " << reason;
    }
    plugin->destroy(instance);
    EXPECT_EQ(counter.whole, 0) << name;
    ASSERT_EQ(counter.single.size(), 2u) << name;  // itself and its one neighbour
    EXPECT_TRUE(counter.single.count(500) && counter.single.count(499)) << name;
    // At most now and next (the discrete law's F(k+1)) per follower and step.
    for (const auto& [follower, calls] : counter.single) EXPECT_LE(calls, 2 * kSteps) << name;
    EXPECT_GT(counter.single.at(499), 0) << name << " never sampled";
  }
}

// A per-agent law from the literature, follower 1 of the paper's graph (hears the leader and
// follower 6) fed a moving leader and neighbour: reset() takes its state (adaptive gain,
// estimate, super-twisting integral) back to the start, so a second run repeats the commands.
TEST_F(FormationPluginTest, LiteratureAgentsResetToTheirStart) {
  for (const char* name : {"vs_tracking_agent", "super_twisting_agent", "adaptive_tracking_agent",
                           "observer_tracking_agent", "terminal_smc_agent"}) {
    SCOPED_TRACE(name);
    const int neighbours[1] = {5};
    const double weights[1] = {1.0};
    const mjfNeighbourhood hood{0, 6, 1.0, 1, neighbours, weights};
    const mjfPlugin* plugin = Plugin(name);
    std::string error;
    void* instance = Create(plugin, {}, &error, 0.01, true, &hood);
    ASSERT_NE(instance, nullptr) << error;
    mjfVehicleState self{};
    mjfSetpoint setpoint{};
    mjfMessage leader{}, neighbour{}, outgoing{};
    neighbour.sender = 6;  // vehicle index of follower 5
    mjfAgentInput input{};
    input.follower = 1;
    input.self = &self;
    input.leader = &leader;
    input.n_messages = 1;
    input.messages = &neighbour;
    input.n_rounds = 1;
    input.outgoing = &outgoing;
    char reason[256] = "";
    mjfStepContext step{};
    step.timestep = 0.01;
    step.n_vehicles = 7;
    step.setpoints = &setpoint;
    step.agent = &input;
    step.error = reason;
    step.error_size = sizeof(reason);
    auto run = [&] {
      std::vector<double> commands;
      for (int s = 0; s < 300; ++s) {
        step.step = s;
        step.time = 0.01 * s;
        leader.state.pos[0] = 3.0 * step.time;  // the leader and follower 6 move off at 3 m/s
        leader.state.vel[0] = 3.0;
        neighbour.state.pos[1] = -2.0 + 3.0 * step.time;
        neighbour.state.vel[1] = 3.0;
        EXPECT_EQ(plugin->compute(instance, &step), 0) << reason;
        commands.push_back(setpoint.acc[0]);
        commands.push_back(setpoint.acc[1]);
      }
      return commands;
    };
    const std::vector<double> first = run();
    plugin->reset(instance);
    EXPECT_EQ(run(), first);
    EXPECT_NE(first.front(), first.back());  // the commands change over the run
    plugin->destroy(instance);
  }
}
