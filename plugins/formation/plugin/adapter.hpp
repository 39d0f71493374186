// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the formation adapters share: reading the swarm from the step context into the
// core's layout, writing follower setpoints, and building graph/shape/gains from create().
#ifndef MJFORMATION_PLUGINS_FORMATION_ADAPTER_HPP_
#define MJFORMATION_PLUGINS_FORMATION_ADAPTER_HPP_

#include <mjformation/plugin.h>

#include <cstddef>
#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/linear_consensus.hpp>
#include <mjformation/formation/literature_agents.hpp>
#include <mjformation/formation/shape.hpp>
#include <mjformation/formation/sliding.hpp>
#include <mjformation/plugin_contract.hpp>
#include <mjformation/plugin_util.hpp>
#include <type_traits>
#include <utility>
#include <vector>

namespace mjf::formation::adapter {

// Attribute keys (short, lowercase).
inline constexpr char kKeyGains[] = "k";
inline constexpr char kKeyRho[] = "rho";
inline constexpr char kKeyEps[] = "eps";
// The ones the runner reads are the contract's (mjformation/plugin_contract.hpp).
inline constexpr const char* kKeyQ = plugin::contract::kQ;
inline constexpr const char* kKeyPeriod = plugin::contract::kPeriod;
inline constexpr const char* kKeyUMin = plugin::contract::kUMin;
inline constexpr const char* kKeyUMax = plugin::contract::kUMax;
inline constexpr char kKeyCompensation[] = "compensation";
inline constexpr char kKeyReaching[] = "reaching";
inline constexpr char kKeySign[] = "sign";
inline constexpr char kKeyBoundaryLayer[] = "boundary_layer";
inline constexpr char kKeyEta0[] = "eta0";
inline constexpr char kKeyKp[] = "kp";
inline constexpr char kKeyKv[] = "kv";
inline constexpr const char* kKeyAccelLimit = plugin::contract::kAccelLimit;
inline constexpr char kKeyReachAccel[] = "reach_accel";

// 'accel_limit': "none" (+infinity: the paper's law) or a number in m/s^2. "vehicle" is
// resolved by the host into the followers' smallest bound before create() (the formation
// plugin sees no vehicle); reaching the plugin unresolved it is refused. Throws naming the key.
double ParseAccelLimit(const plugin::Attributes& attributes);

// The graph and shape handed to a formation plugin's create(); checks that they exist, agree
// with n_vehicles and that the graph has a spanning tree (Assumption 2). Throws on failure.
struct SwarmSetup {
  explicit SwarmSetup(const mjfCreateContext* ctx);
  formation::Graph graph;
  formation::AbiShape shape;
};

formation::SlidingGains ParseGains(const plugin::Attributes& attributes);

// smc_discrete's attributes, shared by its swarm-level and per-agent plugins (smc_discrete.cc).
extern const mjfAttribute kDiscreteAttributes[];
extern const int kDiscreteAttributeCount;
formation::DiscreteSmcParams ParseDiscreteParams(const plugin::Attributes& attributes);
// smc_continuous's and consensus_linear's, likewise.
extern const mjfAttribute kContinuousAttributes[];
extern const int kContinuousAttributeCount;
formation::ContinuousSmcParams ParseContinuousParams(const plugin::Attributes& attributes);
extern const mjfAttribute kConsensusAttributes[];
extern const int kConsensusAttributeCount;
formation::LinearConsensusParams ParseConsensusParams(const plugin::Attributes& attributes);
// The laws from the literature's, likewise (<law>.cc; the per-agent create validates them).
extern const mjfAttribute kVsTrackingAttributes[];
extern const int kVsTrackingAttributeCount;
formation::VsTrackingParams ParseVsTrackingParams(const plugin::Attributes& attributes);
extern const mjfAttribute kSuperTwistingAttributes[];
extern const int kSuperTwistingAttributeCount;
formation::SuperTwistingParams ParseSuperTwistingParams(const plugin::Attributes& attributes);
extern const mjfAttribute kAdaptiveTrackingAttributes[];
extern const int kAdaptiveTrackingAttributeCount;
formation::AdaptiveTrackingParams ParseAdaptiveTrackingParams(const plugin::Attributes& attributes);
extern const mjfAttribute kObserverTrackingAttributes[];
extern const int kObserverTrackingAttributeCount;
formation::ObserverTrackingParams ParseObserverTrackingParams(const plugin::Attributes& attributes);
extern const mjfAttribute kTerminalSmcAttributes[];
extern const int kTerminalSmcAttributeCount;
formation::TerminalSmcParams ParseTerminalSmcParams(const plugin::Attributes& attributes);
// Physics steps per sample period T; throws when T is not a whole number of steps.
int64_t StepsPerSample(double period, double timestep);

// Preallocated buffers in the core's layout, filled from a step context.
class SwarmBuffers {
 public:
  explicit SwarmBuffers(int n_followers);
  // Copies leader and follower pos/vel (x, y) from ctx->states; false if ctx does not match
  // the swarm's size or a state is not finite.
  bool Read(const mjfStepContext* ctx);
  formation::FormationInput Input() const;
  int n() const { return n_; }
  std::vector<double> leader_pv, follower_pv, shape_now, shape_next;

 private:
  int n_;
};

// What a law offers that the defaults of SwarmInstance and SwarmCreate use when it is there.
namespace law_detail {
template <typename Law, typename = void>
struct UpdatesWithTime : std::false_type {};
template <typename Law>
struct UpdatesWithTime<Law, std::void_t<decltype(std::declval<Law&>().Update(
                                std::declval<const formation::FormationInput&>(), 0.0))>>
    : std::true_type {};
template <typename Law, typename = void>
struct HasReset : std::false_type {};
template <typename Law>
struct HasReset<Law, std::void_t<decltype(std::declval<Law&>().Reset())>> : std::true_type {};
template <typename Instance, typename = void>
struct HasConfigure : std::false_type {};
template <typename Instance>
struct HasConfigure<
    Instance, std::void_t<decltype(Instance::Configure(std::declval<const mjfCreateContext*>()))>>
    : std::true_type {};
}  // namespace law_detail

// What a formation plugin instance holds: its copy of the shape, the pure controller and the
// buffers its compute() fills; with the defaults of a law evaluated every physics step.
template <typename Controller>
struct SwarmInstance {
  using Law = Controller;
  template <typename Params>
  SwarmInstance(const SwarmSetup& setup, const Params& params)
      : shape(setup.shape), controller(setup.graph, params), buffers(setup.graph.num_followers()) {}
  // A law evaluated every physics step updates on each, with the host's time when its state
  // advances with it (an integral, an adaptive gain, an estimate); a sampled law hides this.
  void Sample(const mjfStepContext* ctx) {
    if constexpr (law_detail::UpdatesWithTime<Controller>::value) {
      controller.Update(buffers.Input(), ctx->time);
    } else {
      controller.Update(buffers.Input());
    }
  }
  // The law's s_i; a law without a sliding variable hides this with nullptr.
  const double* sliding() const { return controller.sliding().data(); }
  // Back to the state before the first step: the law's Reset(), or nothing for a law whose
  // output is a function of each step's input alone (no Reset()).
  void Reset() {
    if constexpr (law_detail::HasReset<Controller>::value) controller.Reset();
  }
  // The law's state; the buffers are filled from the step before they are read (not state). A
  // law with state of its own (a sample phase) visits it after this.
  template <typename Visit>
  void VisitState(Visit& visit) {
    controller.VisitState(visit);
  }
  formation::AbiShape shape;
  Controller controller;
  SwarmBuffers buffers;
};

// Writes follower i's (vehicle i+1) slot: pos[0..1] = leader pos + f_ip, vel[0..1] = leader
// vel + f_iv. Leaves acc/pos/vel[2] and yaw alone.
void WriteSlots(const SwarmBuffers& buffers, mjfSetpoint* setpoints);
// Writes acc[0..1] = acceleration[2i..2i+1] and, unless sliding is null, sliding[0..1].
void WriteCommands(int n, const double* acceleration, const double* sliding,
                   mjfSetpoint* setpoints);

// The create, compute, reset and destroy every swarm-level law shares; the law's own part is its
// Instance (one file per law), a SwarmInstance<Controller> with:
//   Config, and either static void Read(const plugin::Attributes&, Config*): its attributes,
//     which SwarmCreate then checks (Config::Validate()), or, for a Config that needs more than
//     the attributes, static Config Configure(const mjfCreateContext*), which reads and checks
//     it; either way before the graph and shape are read;
//   Instance(const SwarmSetup&, const Config&) (SwarmInstance's when Config is the law's params);
//   void Sample(const mjfStepContext*): updates the controller once F(t) is in buffers.shape_now
//     (SwarmInstance's: every step);
//   const double* sliding() const: the s_i to write, or nullptr for a law without one
//     (SwarmInstance's: the law's sliding());
//   void Reset(): back to the state before the first step (SwarmInstance's: the law's Reset());
//   template <typename Visit> void VisitState(Visit&): its state (SwarmInstance's: the law's,
//     which must have one: a law without VisitState does not compile here).
template <typename Instance>
typename Instance::Config Configure(const mjfCreateContext* ctx) {
  if constexpr (law_detail::HasConfigure<Instance>::value) {
    return Instance::Configure(ctx);
  } else {
    typename Instance::Config config;
    Instance::Read(plugin::Attributes(ctx), &config);
    config.Validate();
    return config;
  }
}

template <typename Instance>
void* SwarmCreate(const mjfCreateContext* ctx) {
  return plugin::CreateOrExplain(ctx, [&]() -> void* {
    const typename Instance::Config config = Configure<Instance>(ctx);
    const SwarmSetup setup(ctx);
    return new Instance(setup, config);
  });
}

template <typename Instance>
int SwarmCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<Instance*>(instance);
  SwarmBuffers& buffers = self->buffers;
  if (!buffers.Read(ctx))
    return mjf::plugin::Fail(
        ctx, "the step does not carry 1 + n_followers vehicle states and setpoints");
  self->shape.Evaluate(ctx->time, buffers.shape_now.data());
  self->Sample(ctx);
  WriteSlots(buffers, ctx->setpoints);
  WriteCommands(buffers.n(), self->controller.acceleration().data(), self->sliding(),
                ctx->setpoints);
  return 0;
}

template <typename Instance>
void SwarmReset(void* instance) {
  static_cast<Instance*>(instance)->Reset();
}

template <typename Instance>
void SwarmDestroy(void* instance) {
  delete static_cast<Instance*>(instance);
}

// The descriptor of a swarm-level formation plugin whose instance is Instance (report: null for
// a law with nothing to report).
template <typename Instance, size_t kAttributes>
constexpr mjfPlugin SwarmPlugin(const char* name, const char* doc,
                                const mjfAttribute (&attributes)[kAttributes],
                                void (*report)(void*, mjfReportFn, void*) = nullptr) {
  static_assert(plugin::kHasVisitState<typename Instance::Law>,
                "a formation law lists its state: template <typename Visit> void "
                "VisitState(Visit&) (mjformation/plugin_state.hpp)");
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_FORMATION,
          doc,
          static_cast<int>(kAttributes),
          attributes,
          0,
          nullptr,
          &SwarmCreate<Instance>,
          &SwarmCompute<Instance>,
          &SwarmReset<Instance>,
          &SwarmDestroy<Instance>,
          report,
          &plugin::StateSizeOf<Instance>,
          &plugin::GetStateOf<Instance>,
          &plugin::SetStateOf<Instance>};
}

// The descriptors, one per file (register.cc lists them).
extern const mjfPlugin kSmcContinuous;    // smc_continuous.cc: eq. (30) / (33)
extern const mjfPlugin kSmcDiscrete;      // smc_discrete.cc: eq. (48) / (53), zero-order hold
extern const mjfPlugin kConsensusLinear;  // consensus_linear.cc: linear baseline
// Their per-agent versions (AgentPlugin<Law>, agent_adapter.hpp):
extern const mjfPlugin kSmcDiscreteAgent;      // smc_discrete_agent.cc: eq. (48), per follower
extern const mjfPlugin kSmcContinuousAgent;    // smc_continuous_agent.cc: eq. (30), per follower
extern const mjfPlugin kConsensusLinearAgent;  // consensus_linear_agent.cc: linear, per follower
// The laws from the literature (one file each, the maths in src/ of the same name):
extern const mjfPlugin kVsTracking;        // vs_tracking.cc: Cao & Ren, IEEE TAC 2012
extern const mjfPlugin kSuperTwisting;     // super_twisting.cc: Levant 1993 on s_i = K e_i
extern const mjfPlugin kAdaptiveTracking;  // adaptive_tracking.cc: Li, Liu, Ren & Xie, TAC 2013
extern const mjfPlugin kObserverTracking;  // observer_tracking.cc: Hong, Hu & Gao, Aut. 2006
extern const mjfPlugin kTerminalSmc;       // terminal_smc.cc: Feng, Yu & Man, Automatica 2002
// Their per-agent versions (AgentPlugin<Law> over literature_agents.hpp), <law>_agent.cc:
extern const mjfPlugin kVsTrackingAgent;
extern const mjfPlugin kSuperTwistingAgent;
extern const mjfPlugin kAdaptiveTrackingAgent;
extern const mjfPlugin kObserverTrackingAgent;
extern const mjfPlugin kTerminalSmcAgent;

}  // namespace mjf::formation::adapter

#endif  // MJFORMATION_PLUGINS_FORMATION_ADAPTER_HPP_
