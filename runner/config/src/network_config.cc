// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [execution] and [network]: how the formation protocol runs, and the simulated links it runs
// over (docs/NETWORK.md). Every value is checked here, before anything runs.
#include "network_config.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>
#include <sstream>

#include "mjformation/time_steps.hpp"
#include "section_reader.hpp"

namespace mjf::runner {
namespace {

const char* const kLinkKeys[] = {"rate",        "latency",    "jitter",     "loss", "loss_model",
                                 "burst_enter", "burst_exit", "burst_loss", "range"};

// Marks every key a section knows, so that RejectUnknown lists all of them.
void Know(SectionReader& keys, const std::set<std::string>& known) {
  for (const auto& k : known) keys.MarkUsed(k);
}

// The network delivers at physics steps: a latency that is not a whole number of steps would
// be rounded up without saying so (0.5 ms behaving as 1 ms), so it is refused.
void RequireWholeStepLatency(const SectionReader& keys, double latency, double timestep) {
  if (WholeSteps(latency, timestep) >= 0) return;
  std::ostringstream out;
  out << "latency " << latency << " s is not a whole number of physics steps (timestep " << timestep
      << " s): messages are delivered at steps, so it would be rounded up to "
      << StepsAtOrAfter(latency, timestep) * timestep
      << " s; use a multiple of the timestep or a smaller timestep";
  keys.Fail("latency", out.str());
}

// The link keys of the section on top of `base`; every value checked.
network::LinkParams ReadLinkParams(SectionReader& keys, const network::LinkParams& base,
                                   double timestep, double duration) {
  network::LinkParams p = base;
  if (const toml::node* node = keys.Node("rate")) {
    const double rate = keys.Number("rate", 0.0);
    if (!(rate > 0.0)) keys.FailAt(node, "rate", "must be > 0 Hz");
    const int64_t steps = WholeSteps(1.0 / rate, timestep);
    if (steps < 1) {
      std::ostringstream out;
      out << "a broadcast every 1/" << rate << " s is not a whole number of physics steps ("
          << timestep << " s): use 1/(n * timestep) Hz, e.g. " << 1.0 / timestep << " or "
          << 1.0 / (20 * timestep);
      keys.FailAt(node, "rate", out.str());
    }
    p.period_steps = steps;
  }
  // Bounded by the run: a later message never arrives, and the delay in steps must fit int64.
  const std::string within = fmt::format("must be in [0, {}] s (the run's duration)", duration);
  p.latency = keys.Number("latency", p.latency);
  if (!(p.latency >= 0.0 && p.latency <= duration)) keys.Fail("latency", within);
  if (keys.Has("latency")) RequireWholeStepLatency(keys, p.latency, timestep);
  p.jitter = keys.Number("jitter", p.jitter);
  if (!(p.jitter >= 0.0 && p.jitter <= duration)) keys.Fail("jitter", within);
  if (p.latency + p.jitter > duration) {
    keys.Fail(keys.Has("jitter") ? "jitter" : "latency", "latency + jitter " + within);
  }
  p.loss = keys.Number("loss", p.loss);
  if (!(p.loss >= 0.0 && p.loss <= 1.0)) {
    keys.Fail("loss", "must be a probability in [0, 1]");
  }
  p.loss_model = keys.Enum("loss_model", p.loss_model, kLossModelWords);
  for (auto [key, value] :
       {std::pair{"burst_enter", &p.burst_enter}, std::pair{"burst_exit", &p.burst_exit},
        std::pair{"burst_loss", &p.burst_loss}}) {
    *value = keys.Number(key, *value);
    if (!(*value >= 0.0 && *value <= 1.0)) {
      keys.Fail(key, "must be a probability in [0, 1] (Gilbert-Elliott burst model)");
    }
  }
  if (p.loss_model == network::LossModel::kGilbertElliott && !(p.burst_exit > 0.0)) {
    keys.Fail("burst_exit",
              "must be > 0 with loss_model = \"gilbert_elliott\" (a burst would never end)");
  }
  if (const toml::node* node = keys.Node("range")) {
    p.range = keys.Number("range", 0.0);
    if (!(p.range > 0.0)) keys.FailAt(node, "range", "must be > 0 m (leave it out: no limit)");
  }
  return p;
}

// A [[network.link]] must name a link of the graph: an edge of [topology] or a leader link.
bool LinkExists(const ExperimentConfig& c, int from, int to) {
  if (to < 1 || to > c.followers || from < 0 || from > c.followers) return false;
  if (from == 0) return c.leader_weight[to - 1] > 0.0;
  for (const auto& e : c.edges) {
    if (e.from == from - 1 && e.to == to - 1) return true;
  }
  return false;
}

void ParseLinkOverrides(const std::string& path, const toml::node* node, ExperimentConfig& c) {
  const SectionReader list(path, nullptr, "network.link");
  const toml::array* array = node->as_array();
  if (!array) list.FailAt(node, "", "expected [[network.link]] tables");
  std::set<std::pair<int, int>> seen;
  std::set<std::string> known(std::begin(kLinkKeys), std::end(kLinkKeys));
  known.insert({"from", "to"});
  for (const toml::node& item : *array) {
    const toml::table* t = item.as_table();
    if (!t) list.FailAt(&item, "", "expected a table with from, to and link keys");
    SectionReader keys(path, t, "network.link");
    Know(keys, known);
    keys.RejectUnknown();
    NetworkConfig::LinkOverride link;
    for (auto [key, value] : {std::pair{"from", &link.from}, std::pair{"to", &link.to}}) {
      const toml::node* v = t->get(key);
      // Range-checked before the conversion to int: 4294967297 is not link 1.
      if (!v || !v->value_exact<int64_t>() || *v->value_exact<int64_t>() < 0 ||
          *v->value_exact<int64_t>() > c.followers) {
        keys.FailAt(
            v ? v : &item, key,
            "expected a vehicle number (0: the leader, 1.." + std::to_string(c.followers) + ")");
      }
      *value = static_cast<int>(*v->value_exact<int64_t>());
    }
    if (!LinkExists(c, link.from, link.to)) {
      keys.FailAt(&item, "from",
                  "the link " + std::to_string(link.from) + " -> " + std::to_string(link.to) +
                      " is not in the graph ([topology] edges, or leader_links for from = 0)");
    }
    if (!seen.insert({link.from, link.to}).second) {
      keys.FailAt(&item, "from",
                  "the link " + std::to_string(link.from) + " -> " + std::to_string(link.to) +
                      " is configured twice");
    }
    link.line = static_cast<int>(item.source().begin.line);
    link.params = ReadLinkParams(keys, c.network.defaults, c.timestep, c.duration);
    c.network.links.push_back(link);
  }
}

void ParseExecution(const std::string& path, const toml::table& t, const ExperimentConfig& c,
                    NetworkConfig& n) {
  SectionReader keys(path, &t, "execution");
  Know(keys, {"mode", "coupling", "jacobi_rounds", "jacobi_divergence", "predict", "clock_offset",
              "clock_drift_ppm", "clock_sync"});
  keys.RejectUnknown();
  n.execution = keys.Enum("mode", Execution::kCentral, kExecutionWords);
  n.coupling = keys.Enum("coupling", Coupling::kLastInput, kCouplingWords);
  if (const toml::node* node = keys.Node("jacobi_rounds")) {
    auto v = node->value_exact<int64_t>();
    if (!v || *v < 1 || *v > 64)
      keys.FailAt(node, "jacobi_rounds", "must be an integer in [1, 64]");
    if (n.coupling != Coupling::kJacobi) {
      keys.FailAt(node, "jacobi_rounds", "needs coupling = \"jacobi\"");
    }
    n.jacobi_rounds = static_cast<int>(*v);
  }
  n.refuse_divergent = keys.Enum("jacobi_divergence", true, kJacobiDivergenceWords);
  if (n.execution == Execution::kCentral && keys.Has("coupling")) {
    keys.Fail("coupling", "needs mode = \"per_agent\" (central mode solves the coupling exactly)");
  }
  ParseExecutionTiming(keys, c, n);
}

}  // namespace

void ParseNetworkSections(const toml::table& root, ExperimentConfig& c) {
  if (const toml::table* t = root.get_as<toml::table>("execution")) {
    ParseExecution(c.source_path, *t, c, c.network);
  }
  const toml::node* node = root.get("network");
  if (!node) return;
  // RejectUnknownSections checked it is a table.
  SectionReader keys(c.source_path, node->as_table(), "network");
  if (c.network.execution != Execution::kPerAgent) {
    keys.FailAt(node, "",
                "needs [execution] mode = \"per_agent\" (central mode is the ideal-network "
                "reference: one instance that sees every state)");
  }
  std::set<std::string> known(std::begin(kLinkKeys), std::end(kLinkKeys));
  known.insert({"link", "rounds", "round_timeout", "round_policy"});
  Know(keys, known);
  keys.RejectUnknown();
  c.network.defaults = ReadLinkParams(keys, network::LinkParams{}, c.timestep, c.duration);
  if (const toml::node* links = keys.Node("link")) ParseLinkOverrides(c.source_path, links, c);
  ParseExchangeRounds(keys, c);
}

}  // namespace mjf::runner
