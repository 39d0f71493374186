// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The trampolines of a Python formation law (docs/PYTHON.md). The runner calls compute() every
// physics step with the GIL released; the law is called (GIL held) once per sample period and
// its input held in between, as smc_discrete holds eq. (48)'s. Slots (leader + f_i, the
// diagnostic reference the adapters write) are written every step, as the C++ adapters do.
#include "python_law.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mjformation/plugin_contract.hpp>
#include <mjformation/plugin_util.hpp>
#include <mjformation/time_steps.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

namespace mjf::python {
namespace {

constexpr int kStateSize = 13;  // pos 3, vel 3, quat 4, gyro 3: mjfVehicleState, in order
static_assert(sizeof(mjfVehicleState) == kStateSize * sizeof(double), "mjfVehicleState layout");
using plugin::kPayloadLeader;
using plugin::kPayloadUsed;

const mjfAttribute kAttributes[] = {
    {"law", nullptr, "key of the Python callable (set by mjformation.run; names it)"},
    {mjf::plugin::contract::kPeriod, "0", "sample period T of the law, s (0: every physics step)"},
};

// Physics steps per sample: period 0 is every step; else a whole number of steps.
int64_t StepsPerSample(const mjfCreateContext* ctx) {
  const std::string text = plugin::Attributes(ctx).String(plugin::contract::kPeriod);
  // strtod, not stod: stod throws "stod" for a period below the smallest normal double
  // (1e-320), where strtod gives the number and WholeSteps finds it zero steps.
  char* end = nullptr;
  const double period = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') {
    throw std::invalid_argument("attribute 'period': expected a number of seconds, got '" + text +
                                "'");
  }
  if (period == 0.0) return 1;
  const int64_t steps = WholeSteps(period, ctx->timestep);
  if (!(period > 0.0) || steps < 1) {
    char step[32];
    std::snprintf(step, sizeof(step), "%g", ctx->timestep);
    throw std::invalid_argument("attribute 'period': T = " + text +
                                " s must be 0 (every physics step) or a positive whole number "
                                "of physics steps of " +
                                step + " s");
  }
  return steps;
}

// "ZeroDivisionError: division by zero": the last line of the traceback Python would print.
std::string LastTracebackLine(py::error_already_set& e) {
  try {
    py::object lines =
        py::module_::import("traceback").attr("format_exception_only")(e.type(), e.value());
    std::string last = py::str(lines[py::int_(-1)]);
    while (!last.empty() && (last.back() == '\n' || last.back() == ' ')) last.pop_back();
    return last;
  } catch (...) {
    return e.what();
  }
}

// Runs `call` with the GIL held; a Python exception or a C++ one becomes the plugin's failure
// reason (the runner ends the run, complete = false, with it).
template <typename Call>
int Guarded(const mjfStepContext* ctx, Call call) {
  std::string reason;
  {
    py::gil_scoped_acquire gil;
    try {
      call();
      return 0;
    } catch (py::error_already_set& e) {
      reason = LastTracebackLine(e);
    } catch (const std::exception& e) {
      reason = e.what();
    }
  }
  if (ctx->error && ctx->error_size > 0)
    std::snprintf(ctx->error, ctx->error_size, "%s", reason.c_str());
  return 1;
}

template <typename Make>
void* CreateGuarded(const mjfCreateContext* ctx, Make make) {
  py::gil_scoped_acquire gil;
  try {
    return make();
  } catch (py::error_already_set& e) {
    std::snprintf(ctx->error, ctx->error_size, "%s", LastTracebackLine(e).c_str());
  } catch (const std::exception& e) {
    std::snprintf(ctx->error, ctx->error_size, "%s", e.what());
  }
  return nullptr;
}

py::array_t<double> Copy(const double* data, std::vector<py::ssize_t> shape) {
  py::array_t<double> out(shape);
  std::memcpy(out.mutable_data(), data, static_cast<size_t>(out.size()) * sizeof(double));
  return out;
}

// What a law's output must be: an array of exactly `shape` (docs/PYTHON.md: a wrong shape ends
// the run; a (2, N) array has the element count of an (N, 2) one but not its meaning), of
// finite-or-not doubles (the runner checks finiteness).
void ReadInput(const py::object& result, const std::vector<py::ssize_t>& shape, double* out,
               const char* expected) {
  // forcecast alone would read the strings "0.0" as numbers: only numbers are numbers.
  if (const py::array any = py::array::ensure(result)) {
    const char kind = any.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u') {
      throw std::runtime_error("the formation law returned an array of " +
                               py::str(any.dtype()).cast<std::string>() +
                               ", expected numbers: " + expected);
    }
  }
  auto u = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result);
  const bool same_shape =
      u && u.ndim() == static_cast<py::ssize_t>(shape.size()) &&
      std::equal(shape.begin(), shape.end(), u.shape(), [](auto a, auto b) { return a == b; });
  if (!same_shape) {
    // The shapes first: a truncated repr of a large array does not show them.
    auto text = [](const std::vector<py::ssize_t>& dims) {
      std::string t = "(";
      for (size_t k = 0; k < dims.size(); ++k) {
        t += (k ? ", " : "") + std::to_string(dims[k]);
      }
      return t + (dims.size() == 1 ? ",)" : ")");
    };
    const std::string got =
        u ? "an array of shape " + text(std::vector<py::ssize_t>(u.shape(), u.shape() + u.ndim()))
          : std::string(py::str(py::type::of(result).attr("__name__")).cast<std::string>()) +
                " (not convertible to an array of numbers)";
    throw std::runtime_error("the formation law returned " + got + ", expected " + text(shape) +
                             ": " + expected);
  }
  std::memcpy(out, u.data(), static_cast<size_t>(u.size()) * sizeof(double));
}

// ---- one instance per swarm ---------------------------------------------------------------

struct Central {
  py::object law;    // law(t, states, offsets, graph) -> (N, 2)
  py::object graph;  // mjformation.Graph, built once
  mjfShape shape{};
  int n = 0;
  int64_t steps_per_sample = 1;
  double period = 0;
  int64_t calls = 0;
  bool has_sample = false;
  std::vector<double> offsets, input;
};

py::object GraphInfo(const mjfGraph& g) {
  py::array_t<double> leader({static_cast<py::ssize_t>(g.n_followers)});
  py::array_t<double> adjacency(
      {static_cast<py::ssize_t>(g.n_followers), static_cast<py::ssize_t>(g.n_followers)});
  std::memcpy(leader.mutable_data(), g.leader_weight, g.n_followers * sizeof(double));
  std::fill(adjacency.mutable_data(), adjacency.mutable_data() + adjacency.size(), 0.0);
  for (int e = 0; e < g.n_edges; ++e) {
    adjacency.mutable_at(g.edge_to[e], g.edge_from[e]) = g.edge_weight[e];  // a_ij: edge j -> i
  }
  py::dict info;
  info["leader_weight"] = leader;
  info["adjacency"] = adjacency;
  return std::move(info);
}

void* CreateCentral(const mjfCreateContext* ctx) {
  return CreateGuarded(ctx, [&]() -> void* {
    if (!ctx->graph || !ctx->shape)
      throw std::invalid_argument("the host passed no graph or shape");
    auto self = std::make_unique<Central>();
    self->n = ctx->graph->n_followers;
    self->shape = *ctx->shape;
    self->steps_per_sample = StepsPerSample(ctx);
    self->period = self->steps_per_sample * ctx->timestep;
    self->offsets.assign(6 * self->n, 0.0);
    self->input.assign(2 * self->n, 0.0);
    py::tuple resolved =
        py::module_::import("mjformation._laws")
            .attr("resolve_central")(plugin::Attributes(ctx).String("law"), GraphInfo(*ctx->graph));
    self->law = resolved[0];
    self->graph = resolved[1];
    return self.release();
  });
}

void CallCentral(Central& self, const mjfStepContext* ctx) {
  const py::ssize_t v = ctx->n_vehicles, n = self.n;
  py::object u = self.law(ctx->time, Copy(&ctx->states[0].pos[0], {v, kStateSize}),
                          Copy(self.offsets.data(), {n, 6}), self.graph);
  ReadInput(u, {self.n, 2}, self.input.data(), "an (n_followers, 2) array of accelerations");
  ++self.calls;
}

int ComputeCentral(void* instance, const mjfStepContext* ctx) {
  auto& self = *static_cast<Central*>(instance);
  if (ctx->n_vehicles != self.n + 1 || !ctx->states || !ctx->setpoints) {
    std::snprintf(ctx->error, ctx->error_size, "the step does not carry 1 + %d vehicles", self.n);
    return 1;
  }
  self.shape.evaluate(self.shape.self, ctx->time, self.offsets.data());
  if (!self.has_sample || ctx->step % self.steps_per_sample == 0) {
    if (Guarded(ctx, [&] { CallCentral(self, ctx); }) != 0) return 1;
    self.has_sample = true;
  }
  const mjfVehicleState& leader = ctx->states[0];
  for (int i = 0; i < self.n; ++i) {
    mjfSetpoint& sp = ctx->setpoints[i + 1];
    for (int axis = 0; axis < 2; ++axis) {
      sp.pos[axis] = leader.pos[axis] + self.offsets[6 * i + axis];
      sp.vel[axis] = leader.vel[axis] + self.offsets[6 * i + 2 + axis];
      sp.acc[axis] = self.input[2 * i + axis];  // zero-order hold between samples
    }
  }
  return 0;
}

void ResetCentral(void* instance) { static_cast<Central*>(instance)->has_sample = false; }

void DestroyCentral(void* instance) {
  py::gil_scoped_acquire gil;
  delete static_cast<Central*>(instance);
}

void Report(int64_t calls, double period, int64_t steps, mjfReportFn emit, void* user) {
  emit(user, plugin::contract::kPeriod, period);
  emit(user, "steps_per_sample", static_cast<double>(steps));
  emit(user, "python_calls", static_cast<double>(calls));
}

void ReportCentral(void* instance, mjfReportFn emit, void* user) {
  const auto& self = *static_cast<const Central*>(instance);
  Report(self.calls, self.period, self.steps_per_sample, emit, user);
}

// ---- one instance per follower (per-agent execution) ---------------------------------------

struct Agent {
  py::object law;  // law(t, me, messages, leader, offsets) -> (2,)
  mjfShape shape{};
  int follower = 0, n = 0;
  double leader_weight = 0;
  plugin::NeighbourInbox inbox;  // the neighbours' messages and the leader's state
  int64_t steps_per_sample = 1;
  double period = 0;
  int64_t calls = 0;
  bool has_sample = false;
  double input[2] = {0, 0};
  std::vector<double> offsets;
};

py::object NeighbourhoodInfo(const mjfNeighbourhood& h) {
  py::dict info;
  info["follower"] = h.follower;
  info["n_followers"] = h.n_followers;
  info["leader_weight"] = h.leader_weight;
  py::list neighbours, weights;
  for (int m = 0; m < h.n_neighbours; ++m) {
    neighbours.append(h.neighbours[m]);
    weights.append(h.weights[m]);
  }
  info["neighbours"] = neighbours;
  info["weights"] = weights;
  return std::move(info);
}

void* CreateAgent(const mjfCreateContext* ctx) {
  return CreateGuarded(ctx, [&]() -> void* {
    if (!ctx->neighbourhood || !ctx->shape) throw std::invalid_argument("per-agent execution only");
    const mjfNeighbourhood& h = *ctx->neighbourhood;
    auto self = std::make_unique<Agent>();
    self->shape = *ctx->shape;
    self->follower = h.follower;
    self->n = h.n_followers;
    self->leader_weight = h.leader_weight;
    self->inbox =
        plugin::NeighbourInbox(std::vector<int>(h.neighbours, h.neighbours + h.n_neighbours));
    self->offsets.assign(6 * self->n, 0.0);
    self->steps_per_sample = StepsPerSample(ctx);
    self->period = self->steps_per_sample * ctx->timestep;
    self->law =
        py::module_::import("mjformation._laws")
            .attr("resolve_agent")(plugin::Attributes(ctx).String("law"), NeighbourhoodInfo(h));
    return self.release();
  });
}

void CallAgent(Agent& a, const mjfStepContext* ctx) {
  const mjfAgentInput& in = *ctx->agent;
  py::dict messages;
  for (size_t m = 0; m < a.inbox.neighbours().size(); ++m) {
    messages[py::int_(a.inbox.neighbours()[m])] =
        Copy(&a.inbox.message(m)->state.pos[0], {kStateSize});
  }
  py::object leader =
      in.leader ? py::object(Copy(&in.leader->state.pos[0], {kStateSize})) : py::object(py::none());
  a.shape.evaluate(a.shape.self, ctx->time, a.offsets.data());
  py::object u = a.law(ctx->time, Copy(&in.self->pos[0], {kStateSize}), messages, leader,
                       Copy(a.offsets.data(), {a.n, 6}));
  ReadInput(u, {2}, a.input, "a (2,) array of accelerations (x, y)");
  ++a.calls;
}

int ComputeAgent(void* instance, const mjfStepContext* ctx) {
  auto& a = *static_cast<Agent*>(instance);
  if (!ctx->agent || !ctx->agent->self || !ctx->setpoints || !ctx->agent->outgoing) {
    std::snprintf(ctx->error, ctx->error_size, "needs per-agent execution (ctx->agent)");
    return 1;
  }
  const mjfAgentInput& in = *ctx->agent;
  // The C++ per-agent plugins' rule: the law is called once every message it needs has come.
  const bool ready = a.inbox.Gather(in, a.leader_weight);
  if (!ready && !a.has_sample) return 0;  // nothing heard yet: the initial setpoint holds
  const bool sampled = ready && (!a.has_sample || ctx->step % a.steps_per_sample == 0);
  if (sampled) {
    if (Guarded(ctx, [&] { CallAgent(a, ctx); }) != 0) return 1;
    a.has_sample = true;
  }
  double f[6];
  a.shape.evaluate_one(a.shape.self, ctx->time, a.follower, f);
  mjfSetpoint& sp = *ctx->setpoints;
  for (int axis = 0; axis < 2; ++axis) {
    const double* leader = a.inbox.leader_pv();
    sp.pos[axis] = a.inbox.knows_leader() ? leader[axis] + f[axis] : in.self->pos[axis];
    sp.vel[axis] = a.inbox.knows_leader() ? leader[2 + axis] + f[2 + axis] : in.self->vel[axis];
    sp.acc[axis] = a.input[axis];
  }
  mjfMessage& out = *in.outgoing;  // relays the leader's state, as the C++ agents do
  out.n_payload = sampled ? kPayloadUsed : 0;
  std::fill(out.payload, out.payload + kPayloadLeader, 0.0);
  std::copy(a.inbox.leader_pv(), a.inbox.leader_pv() + 4, out.payload + kPayloadLeader);
  return 0;
}

void ResetAgent(void* instance) { static_cast<Agent*>(instance)->has_sample = false; }

void DestroyAgent(void* instance) {
  py::gil_scoped_acquire gil;
  delete static_cast<Agent*>(instance);
}

void ReportAgent(void* instance, mjfReportFn emit, void* user) {
  const auto& a = *static_cast<const Agent*>(instance);
  Report(a.calls, a.period, a.steps_per_sample, emit, user);
}

const mjfPlugin kCentral = {MJF_ABI_VERSION, "python", MJF_KIND_FORMATION,
                            "a formation law written in Python (mjformation.run(formation=...))", 2,
                            kAttributes, 0, nullptr, &CreateCentral, &ComputeCentral, &ResetCentral,
                            &DestroyCentral, &ReportCentral,
                            // A Python law's state lives in Python objects: not declared, so
                            // a host that copies or checkpoints instances refuses it.
                            nullptr, nullptr, nullptr};

const mjfPlugin kAgent = {MJF_ABI_VERSION,
                          "python_agent",
                          MJF_KIND_FORMATION_AGENT,
                          "a per-agent formation law written in Python, one callable per follower",
                          2,
                          kAttributes,
                          0,
                          nullptr,
                          &CreateAgent,
                          &ComputeAgent,
                          &ResetAgent,
                          &DestroyAgent,
                          &ReportAgent,
                          nullptr,
                          nullptr,
                          nullptr};

}  // namespace

const mjfPlugin& CentralLawPlugin() { return kCentral; }
const mjfPlugin& AgentLawPlugin() { return kAgent; }

}  // namespace mjf::python
