// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [execution] and [network]: how the formation protocol runs, and the simulated links it runs
// over (docs/NETWORK.md). Every value is checked here, before anything runs.
#include "network_config.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "mjformation/config/source_location.hpp"

namespace mjf::runner {
namespace {

const char* const kLinkKeys[] = {"rate",        "latency",    "jitter",     "loss", "loss_model",
                                 "burst_enter", "burst_exit", "burst_loss", "range"};

// "FILE:LINE: [section] key: message" for one node of the document.
class Where {
 public:
  Where(const std::string& path, std::string section) : path_(path), section_(std::move(section)) {}
  [[noreturn]] void Fail(const toml::node* node, const std::string& key,
                         const std::string& message) const {
    const int line = node ? static_cast<int>(node->source().begin.line) : 0;
    SourceLocation{path_, line, SectionKey(section_, key)}.Fail(message);
  }

 private:
  const std::string& path_;
  std::string section_;
};

double Number(const Where& where, const toml::table& t, const std::string& key, double fallback) {
  const toml::node* node = t.get(key);
  if (!node) return fallback;
  if (auto v = node->value_exact<double>()) {
    if (!std::isfinite(*v)) where.Fail(node, key, "expected a finite number");
    return *v;
  }
  if (auto v = node->value_exact<int64_t>()) return static_cast<double>(*v);
  where.Fail(node, key, "expected a number");
}

std::string Text(const Where& where, const toml::table& t, const std::string& key,
                 const std::string& fallback) {
  const toml::node* node = t.get(key);
  if (!node) return fallback;
  if (auto v = node->value_exact<std::string>()) return *v;
  where.Fail(node, key, "expected a string");
}

void RejectUnknown(const Where& where, const toml::table& t, const std::set<std::string>& known) {
  for (auto&& [key, node] : t) {
    const std::string k(key.str());
    if (known.count(k)) continue;
    std::string list;
    for (const auto& u : known) list += (list.empty() ? "" : ", ") + u;
    where.Fail(&node, k, "unknown key (this section knows: " + list + ")");
  }
}

// The link keys of table `t` on top of `base`; every value checked.
network::LinkParams ReadLinkParams(const Where& where, const toml::table& t,
                                   const network::LinkParams& base, double timestep) {
  network::LinkParams p = base;
  if (const toml::node* node = t.get("rate")) {
    const double rate = Number(where, t, "rate", 0.0);
    if (!(rate > 0.0)) where.Fail(node, "rate", "must be > 0 Hz");
    const double period_steps = 1.0 / (rate * timestep);
    const auto steps = static_cast<int64_t>(std::llround(period_steps));
    if (steps < 1 || std::abs(period_steps - static_cast<double>(steps)) > 1e-6 * period_steps) {
      std::ostringstream out;
      out << "a broadcast every 1/" << rate << " s is not a whole number of physics steps ("
          << timestep << " s): use 1/(n * timestep) Hz, e.g. " << 1.0 / timestep << " or "
          << 1.0 / (20 * timestep);
      where.Fail(node, "rate", out.str());
    }
    p.period_steps = steps;
  }
  p.latency = Number(where, t, "latency", p.latency);
  if (p.latency < 0.0) where.Fail(t.get("latency"), "latency", "must be >= 0 s");
  p.jitter = Number(where, t, "jitter", p.jitter);
  if (p.jitter < 0.0) where.Fail(t.get("jitter"), "jitter", "must be >= 0 s");
  p.loss = Number(where, t, "loss", p.loss);
  if (!(p.loss >= 0.0 && p.loss <= 1.0)) {
    where.Fail(t.get("loss"), "loss", "must be a probability in [0, 1]");
  }
  const std::string model = Text(where, t, "loss_model", "");
  if (model == "bernoulli") {
    p.loss_model = network::LossModel::kBernoulli;
  } else if (model == "gilbert_elliott") {
    p.loss_model = network::LossModel::kGilbertElliott;
  } else if (!model.empty()) {
    where.Fail(t.get("loss_model"), "loss_model",
               "must be \"bernoulli\" or \"gilbert_elliott\" (got \"" + model + "\")");
  }
  for (auto [key, value] :
       {std::pair{"burst_enter", &p.burst_enter}, std::pair{"burst_exit", &p.burst_exit},
        std::pair{"burst_loss", &p.burst_loss}}) {
    *value = Number(where, t, key, *value);
    if (!(*value >= 0.0 && *value <= 1.0)) {
      where.Fail(t.get(key), key, "must be a probability in [0, 1] (Gilbert-Elliott burst model)");
    }
  }
  if (p.loss_model == network::LossModel::kGilbertElliott && !(p.burst_exit > 0.0)) {
    where.Fail(t.get("burst_exit"), "burst_exit",
               "must be > 0 with loss_model = \"gilbert_elliott\" (a burst would never end)");
  }
  if (const toml::node* node = t.get("range")) {
    p.range = Number(where, t, "range", 0.0);
    if (!(p.range > 0.0)) where.Fail(node, "range", "must be > 0 m (leave it out: no limit)");
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
  const Where where(path, "network.link");
  const toml::array* array = node->as_array();
  if (!array) where.Fail(node, "", "expected [[network.link]] tables");
  std::set<std::pair<int, int>> seen;
  std::set<std::string> known(std::begin(kLinkKeys), std::end(kLinkKeys));
  known.insert({"from", "to"});
  for (const toml::node& item : *array) {
    const toml::table* t = item.as_table();
    if (!t) where.Fail(&item, "", "expected a table with from, to and link keys");
    RejectUnknown(where, *t, known);
    NetworkConfig::LinkOverride link;
    for (auto [key, value] : {std::pair{"from", &link.from}, std::pair{"to", &link.to}}) {
      const toml::node* v = t->get(key);
      if (!v || !v->value_exact<int64_t>()) {
        where.Fail(v ? v : &item, key, "expected a vehicle number (0: the leader, 1..N)");
      }
      *value = static_cast<int>(*v->value_exact<int64_t>());
    }
    if (!LinkExists(c, link.from, link.to)) {
      where.Fail(&item, "from",
                 "the link " + std::to_string(link.from) + " -> " + std::to_string(link.to) +
                     " is not in the graph ([topology] edges, or leader_links for from = 0)");
    }
    if (!seen.insert({link.from, link.to}).second) {
      where.Fail(&item, "from",
                 "the link " + std::to_string(link.from) + " -> " + std::to_string(link.to) +
                     " is configured twice");
    }
    link.line = static_cast<int>(item.source().begin.line);
    link.params = ReadLinkParams(where, *t, c.network.defaults, c.timestep);
    c.network.links.push_back(link);
  }
}

void ParseExecution(const std::string& path, const toml::table& t, NetworkConfig& n) {
  const Where where(path, "execution");
  RejectUnknown(where, t, {"mode", "coupling", "jacobi_rounds", "jacobi_divergence"});
  const std::string mode = Text(where, t, "mode", "central");
  if (mode == "per_agent") {
    n.execution = Execution::kPerAgent;
  } else if (mode != "central") {
    where.Fail(t.get("mode"), "mode",
               "must be \"central\" or \"per_agent\" (got \"" + mode + "\")");
  }
  const std::string coupling = Text(where, t, "coupling", "last_input");
  if (coupling == "jacobi") {
    n.coupling = Coupling::kJacobi;
  } else if (coupling == "central_solve") {
    n.coupling = Coupling::kCentralSolve;
  } else if (coupling != "last_input") {
    where.Fail(
        t.get("coupling"), "coupling",
        "must be \"last_input\", \"jacobi\" or \"central_solve\" (got \"" + coupling + "\")");
  }
  if (const toml::node* node = t.get("jacobi_rounds")) {
    auto v = node->value_exact<int64_t>();
    if (!v || *v < 1 || *v > 64) where.Fail(node, "jacobi_rounds", "must be an integer in [1, 64]");
    if (n.coupling != Coupling::kJacobi) {
      where.Fail(node, "jacobi_rounds", "needs coupling = \"jacobi\"");
    }
    n.jacobi_rounds = static_cast<int>(*v);
  }
  const std::string divergence = Text(where, t, "jacobi_divergence", "refuse");
  if (divergence == "warn") {
    n.refuse_divergent = false;
  } else if (divergence != "refuse") {
    where.Fail(t.get("jacobi_divergence"), "jacobi_divergence",
               "must be \"refuse\" or \"warn\" (got \"" + divergence + "\")");
  }
  if (n.execution == Execution::kCentral && t.contains("coupling")) {
    where.Fail(t.get("coupling"), "coupling",
               "needs mode = \"per_agent\" (central mode solves the coupling exactly)");
  }
}

}  // namespace

const char* ToString(Execution value) {
  return value == Execution::kPerAgent ? "per_agent" : "central";
}

const char* ToString(Coupling value) {
  switch (value) {
    case Coupling::kJacobi:
      return "jacobi";
    case Coupling::kCentralSolve:
      return "central_solve";
    default:
      return "last_input";
  }
}

void ParseNetworkSections(const toml::table& root, ExperimentConfig& c) {
  if (const toml::table* t = root.get_as<toml::table>("execution")) {
    ParseExecution(c.source_path, *t, c.network);
  }
  const toml::node* node = root.get("network");
  if (!node) return;
  const Where where(c.source_path, "network");
  const toml::table& t = *node->as_table();  // RejectUnknownSections checked it is a table
  if (c.network.execution != Execution::kPerAgent) {
    where.Fail(node, "",
               "needs [execution] mode = \"per_agent\" (central mode is the ideal-network "
               "reference: one instance that sees every state)");
  }
  std::set<std::string> known(std::begin(kLinkKeys), std::end(kLinkKeys));
  known.insert("link");
  RejectUnknown(where, t, known);
  c.network.defaults = ReadLinkParams(where, t, network::LinkParams{}, c.timestep);
  if (const toml::node* links = t.get("link")) ParseLinkOverrides(c.source_path, links, c);
}

}  // namespace mjf::runner
