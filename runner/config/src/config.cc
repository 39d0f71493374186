// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/config/config.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "mjformation/config/overrides.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/config/source_location.hpp"
#include "network_config.hpp"
#include "realism_config.hpp"
#include "safety_config.hpp"
#include "section_reader.hpp"

namespace mjf::runner {
namespace {

// Reports a problem at a node of the document: "FILE:LINE: [section] key: message".
class Reporter {
 public:
  explicit Reporter(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void Fail(const toml::node* node, const std::string& where,
                         const std::string& message) const {
    NodeLocation(path_, node, where).Fail(message);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Where `node` was given (null: nowhere, a default): its line, or the --set that gave it.
ValueOrigin OriginOf(const toml::node* node) {
  if (!node) return {};
  const auto& path = node->source().path;
  if (path && path->rfind("--set ", 0) == 0) return {0, *path};
  return {static_cast<int>(node->source().begin.line), ""};
}

// The actuator names of [vehicles] `key` (an array), each once across `seen`.
std::vector<std::string> ActuatorNames(SectionReader& vehicles, const Reporter& reporter,
                                       const char* key, std::vector<std::string>* seen) {
  std::vector<std::string> out;
  const toml::array* a = vehicles.Array(key);
  if (!a) return out;
  const std::string where = std::string("[vehicles] ") + key;
  for (const toml::node& item : *a) {
    auto v = item.value_exact<std::string>();
    if (!v || v->empty()) {
      reporter.Fail(&item, where, "expected actuator names, e.g. [\"m1\", \"m2\"]");
    }
    if (std::find(seen->begin(), seen->end(), *v) != seen->end()) {
      reporter.Fail(&item, where, "'" + *v + "' is listed twice");
    }
    seen->push_back(*v);
    out.push_back(*v);
  }
  return out;
}

// [vehicles] thrust and moments: a thrust-and-moment vehicle's four actuators by role, in the
// order the attitude plugin drives them (thrust, moment about body x, y, z).
void ParseThrustAndMoments(SectionReader& vehicles, const Reporter& reporter,
                           const std::function<ValueOrigin(const char*)>& origin,
                           ExperimentConfig* c) {
  vehicles.MarkUsed("thrust");  // known even when absent: the unknown-key message lists them
  vehicles.MarkUsed("moments");
  if (!vehicles.Has("thrust") && !vehicles.Has("moments")) return;
  if (!c->vehicle_rotors.empty()) {
    vehicles.Fail("thrust", "a vehicle has rotors or thrust and moments, not both");
  }
  if (!vehicles.Has("thrust") || !vehicles.Has("moments")) {
    vehicles.Fail(vehicles.Has("thrust") ? "thrust" : "moments",
                  "thrust and moments go together: thrust = \"<actuator>\", moments = "
                  "[\"<about x>\", \"<about y>\", \"<about z>\"]");
  }
  const std::string thrust = vehicles.String("thrust", "");
  if (thrust.empty()) vehicles.Fail("thrust", "must name the model's thrust actuator");
  std::vector<std::string> seen = {thrust};
  const std::vector<std::string> moments = ActuatorNames(vehicles, reporter, "moments", &seen);
  if (moments.size() != 3) {
    vehicles.Fail("moments", "must name 3 actuators (moments about body x, y, z), not " +
                                 std::to_string(moments.size()));
  }
  c->vehicle_actuation = VehicleActuation::kThrustMoments;
  c->vehicle_rotors = seen;  // thrust, then the moments
  c->vehicle_rotors_origin = origin("thrust");
  c->vehicle_moments_origin = origin("moments");
}

// [vehicles] body and rotors (or thrust and moments): how a foreign vehicle model maps onto
// the vehicle contract (docs/VEHICLES.md); whether the model has them is checked when the model
// is adapted.
void ParseVehicleMapping(SectionReader& vehicles, const Reporter& reporter, ExperimentConfig* c) {
  auto origin = [&](const char* key) { return OriginOf(vehicles.Node(key)); };
  c->vehicle_body = vehicles.String("body", "");
  c->vehicle_body_origin = origin("body");
  if (vehicles.Has("body") && c->vehicle_body.empty()) vehicles.Fail("body", "must not be empty");
  if (vehicles.Array("rotors")) {
    c->vehicle_rotors_origin = origin("rotors");
    std::vector<std::string> seen;
    c->vehicle_rotors = ActuatorNames(vehicles, reporter, "rotors", &seen);
    if (c->vehicle_rotors.empty()) vehicles.Fail("rotors", "must name the model's rotors");
  }
  ParseThrustAndMoments(vehicles, reporter, origin, c);
}

// TOML value -> the ABI's attribute string ("3 1" for arrays of numbers).
std::string AttributeText(const Reporter& reporter, const toml::node& node,
                          const std::string& where) {
  if (auto v = node.value_exact<double>()) {
    return fmt::format("{}", *v);  // shortest text that reads back to the same double
  }
  if (auto v = node.value_exact<int64_t>()) return std::to_string(*v);
  if (auto v = node.value_exact<bool>()) return *v ? "true" : "false";
  if (auto v = node.value_exact<std::string>()) return *v;
  if (const toml::array* a = node.as_array()) {
    std::string out;
    for (const toml::node& item : *a) {
      if (item.is_array() || item.is_table()) {
        reporter.Fail(&item, where, "nested arrays are not plugin attributes");
      }
      // ["3", "1"] would read as the numbers 3 1: an array holds numbers or booleans only.
      if (item.is_string()) {
        reporter.Fail(&item, where, "an array attribute holds numbers or booleans, not strings");
      }
      out += (out.empty() ? "" : " ") + AttributeText(reporter, item, where);
    }
    return out;
  }
  reporter.Fail(&node, where, std::string("a plugin attribute cannot be ") + TypeName(node));
}

PluginSection ReadPluginSection(const Reporter& reporter, const toml::table& root,
                                const std::string& name, const std::string& default_plugin,
                                const std::set<std::string>& reserved) {
  PluginSection out;
  out.section = name;
  // Its own keys; every other key is an attribute the chosen plugin declares (plugin host).
  std::set<std::string> own = reserved;
  own.insert("plugin");
  RecordAcceptedKeys(name, own);
  const toml::node* node = root.get(name);
  if (node && !node->is_table()) {
    reporter.Fail(node, "[" + name + "]", "expected a table");
  }
  const toml::table* table = node ? node->as_table() : nullptr;
  out.plugin = default_plugin;
  if (table) {
    const toml::node* p = table->get("plugin");
    if (p) {
      auto v = p->value_exact<std::string>();
      if (!v) reporter.Fail(p, "[" + name + "] plugin", "expected a string (a plugin name)");
      out.plugin = *v;
    }
    const ValueOrigin origin = OriginOf(p ? p : node);
    out.line = p ? origin.line : 0;
    out.origin = origin.argument;
    for (auto&& [key, value] : *table) {
      const std::string k(key.str());
      if (k == "plugin" || reserved.count(k)) continue;
      const SourceLocation at = NodeLocation(reporter.path(), &value, "");
      out.attributes[k] = {AttributeText(reporter, value, "[" + name + "] " + k), at.line,
                           at.path == reporter.path() ? "" : at.path};
      // A plugin's `file` attribute is a path relative to the experiment file, like
      // [formation.shape] file: the experiment runs the same from any working folder.
      if (k == "file" && value.is_string()) {
        out.attributes[k].text = ResolveRelative(out.attributes[k].text, reporter.path());
      }
    }
  }
  if (out.plugin.empty()) {
    reporter.Fail(table, "[" + name + "] plugin", "missing: name the plugin to use");
  }
  return out;
}

// One --set is one key: a line break would let its text carry further keys (applied or not) and
// travel into config.toml's header comment as live lines; no value needs a raw control character
// (a TOML string writes them as escapes: "\n").
void RejectControlCharacters(const std::string& item) {
  const bool control = std::any_of(item.begin(), item.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 || u == 0x7f;
  });
  if (control) {
    throw ConfigError("override '" + OneLineEscaped(item) +
                      "': holds a line break or other control character; give one "
                      "section.key=value per --set (inside a TOML string, write \"\\n\")");
  }
}

}  // namespace

// Applies "section.key=value" overrides by parsing the value as TOML.
void ApplyOverrides(toml::table& root, const std::vector<std::string>& overrides) {
  for (const std::string& item : overrides) {
    RejectControlCharacters(item);
    const auto eq = item.find('=');
    if (eq == std::string::npos) {
      throw ConfigError("override '" + item + "': expected section.key=value");
    }
    std::string path = item.substr(0, eq);
    const std::string value = item.substr(eq + 1);
    toml::table parsed;
    try {
      parsed = toml::parse("v = " + value, "--set " + item);  // the origin errors name
    } catch (const toml::parse_error& e) {
      throw ConfigError("override '" + item + "': value is not TOML (" +
                        std::string(e.description()) + "); quote strings: key=\"text\"");
    }
    // The value alone: `v = <value>` must give the one key v (nothing after the value).
    if (parsed.size() != 1 || !parsed.contains("v")) {
      throw ConfigError("override '" + item + "': expected one value after '='");
    }
    toml::table* table = &root;
    std::size_t start = 0;
    for (std::size_t dot; (dot = path.find('.', start)) != std::string::npos; start = dot + 1) {
      const std::string part = path.substr(start, dot - start);
      if (!table->contains(part)) table->insert(part, toml::table{});
      table = (*table)[part].as_table();
      if (!table) throw ConfigError("override '" + item + "': '" + part + "' is not a table");
    }
    const std::string key = path.substr(start);
    if (key.empty() || (start == 0 && !parsed.get("v")->is_table())) {
      throw ConfigError("override '" + item +
                        "': expected section.key=value, or section={...} to replace a section");
    }
    // section={ plugin = "x" } replaces the section's plain keys (the old ones may not suit x)
    // but keeps its sub-tables that the new value does not give ([formation.shape],
    // [[network.link]]): they describe the experiment, not the plugin.
    toml::node& replacement = *parsed.get("v");
    if (toml::table* old = table->get_as<toml::table>(key); old && replacement.is_table()) {
      toml::table& fresh = *replacement.as_table();
      for (auto&& [name, node] : *old) {
        if ((node.is_table() || node.is_array_of_tables()) && !fresh.contains(name.str()))
          fresh.insert(name.str(), std::move(node));
      }
    }
    // Moved, not copied: a copy of a toml++ node drops its source (the --set origin).
    table->insert_or_assign(key, std::move(replacement));
  }
}

std::vector<ExperimentConfig::Edge> GeneratedEdges(int n, bool ring) {
  std::vector<ExperimentConfig::Edge> edges;
  for (int i = 1; i < n; ++i) edges.push_back({i - 1, i, 1.0});
  if (ring && n > 2) edges.push_back({n - 1, 0, 1.0});
  return edges;
}

namespace {

// The TOML document with overrides applied; syntax errors as FILE:LINE:COLUMN.
toml::table ParseDocument(const std::string& text, const std::string& path,
                          const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream out;
    out << path << ":" << e.source().begin.line << ":" << e.source().begin.column
        << ": TOML syntax error: " << e.description();
    throw ConfigError(out.str());
  }
  ApplyOverrides(root, overrides);
  return root;
}

void RejectUnknownSections(const Reporter& reporter, const toml::table& root) {
  for (auto&& [key, node] : root) {
    const std::string name(key.str());
    if (std::find(std::begin(kExperimentSections), std::end(kExperimentSections), name) ==
        std::end(kExperimentSections)) {
      std::string known;
      for (const char* s : kExperimentSections)
        known += (known.empty() ? "" : ", ") + std::string(s);
      reporter.Fail(&node, SectionKey(name), "unknown section (known: " + known + ")");
    }
    if (!node.is_table()) reporter.Fail(&node, name, "expected a [section] table");
  }
}

// The default run folder is runs/<name>: a name is one plain folder name, never a path.
void CheckRunName(const SectionReader& run, const std::string& name) {
  if (name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos ||
      std::any_of(name.begin(), name.end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; })) {
    run.Fail("name",
             "must be a plain folder name (no '/', '\\', '..' or control characters): "
             "runs go into runs/<name>");
  }
}

// [run] paper_experiment, range-checked before the conversion to int.
int PaperExperiment(SectionReader& run) {
  const int64_t paper = run.Integer("paper_experiment", 0);
  if (paper < 0 || paper > 3) run.Fail("paper_experiment", "must be 1, 2 or 3 (or 0: none)");
  return static_cast<int>(paper);
}

// [run] threads, range-checked before the conversion to int, with where it was given.
void ReadThreads(SectionReader& run, ExperimentConfig& c) {
  const int64_t threads = run.Integer("threads", 1);
  if (threads < 1 || threads > kMaxThreads) {
    run.Fail("threads", fmt::format("must be in [1, {}] (1: one model)", kMaxThreads));
  }
  c.threads = static_cast<int>(threads);
  c.threads_origin = OriginOf(run.Node("threads"));
}

// [run]'s duration, time step, record rate and reaching band, each against its range.
void CheckRunTiming(const SectionReader& run, const ExperimentConfig& c) {
  if (c.duration <= 0) run.Fail("duration", "must be > 0 s");
  if (c.timestep <= 0 || c.timestep > 0.01) run.Fail("timestep", "must be in (0, 0.01] s");
  if (c.duration / c.timestep > 1e10) {  // step counts stay far inside int64
    run.Fail("duration", "is more than 1e10 physics steps of [run] timestep");
  }
  // 0 (or no key) stands for the law's own band; a negative band would be read the same way.
  if (c.reaching_band < 0) {
    run.Fail("reaching_band", "must be >= 0 (0 or no key: the formation law's delta)");
  }
  if (c.record_rate <= 0 || c.record_rate > 1.0 / c.timestep) {
    run.Fail("record_rate", "must be in (0, 1/timestep] Hz");
  }
}

// [run] plugin_path: folders relative to the experiment file. With `must_exist`, a folder that
// is not there is refused by name: a typo would otherwise go unnoticed until a plugin it holds is
// "not found".
void ReadPluginPath(const Reporter& reporter, SectionReader& run, const std::string& path,
                    bool must_exist, ExperimentConfig& c) {
  const toml::array* a = run.Array("plugin_path");
  if (!a) return;
  for (const toml::node& item : *a) {
    auto v = item.value_exact<std::string>();
    if (!v) reporter.Fail(&item, "[run] plugin_path", "expected strings (folders)");
    const std::string folder = ResolveRelative(*v, path);
    if (must_exist && !IsDirectory(folder)) {
      reporter.Fail(&item, "[run] plugin_path",
                    "'" + *v + "' is not a folder" + (folder == *v ? "" : " (" + folder + ")"));
    }
    c.plugin_path.push_back(folder);
  }
}

void ParseRunSection(const Reporter& reporter, SectionReader run, const std::string& path,
                     bool plugin_folders, ExperimentConfig& c) {
  c.name = run.String("name", "");
  c.duration = run.Number("duration", c.duration);
  c.timestep = run.Number("timestep", c.timestep);
  const int64_t seed = run.Integer("seed", 1);
  if (seed < 0) run.Fail("seed", "must be >= 0");
  c.seed = static_cast<uint64_t>(seed);
  c.record_rate = run.Number("record_rate", c.record_rate);
  const bool window_given = run.Has("metric_window");
  {
    auto w = run.Numbers("metric_window", {c.metric_window[0], c.metric_window[1]}, 2);
    c.metric_window = {w[0], w[1]};
  }
  c.paper_experiment = PaperExperiment(run);
  c.reaching_band = run.Number("reaching_band", 0.0);
  c.record_leader_acceleration = run.Bool("record_leader_acceleration", false);
  run.MarkUsed("stop_on");  // read with [safety] (safety_config.cc)
  ReadThreads(run, c);
  ReadPluginPath(reporter, run, path, plugin_folders, c);
  run.RejectUnknown();
  CheckRunTiming(run, c);
  if (!(c.metric_window[0] < c.metric_window[1])) {
    run.Fail("metric_window", "expected [start, end] with start < end");
  }
  if (!window_given) {
    // Default: the last 37.5 % of the run, Table 1's [25, 40] s for the paper's 40 s runs.
    c.metric_window = {0.625 * c.duration, c.duration};
  }
  // A window reaching past the run would average fewer samples than the user asked for.
  if (c.metric_window[0] < 0 || c.metric_window[1] > c.duration + 1e-9) {
    run.Fail("metric_window",
             fmt::format("[{}, {}] s lies outside the run [0, {}] s (a shortened run needs its "
                         "window too, e.g. --set 'run.metric_window=[{}, {}]')",
                         c.metric_window[0], c.metric_window[1], c.duration, 0.625 * c.duration,
                         c.duration));
  }
  CheckRunName(run, c.name);
  if (c.name.empty()) {
    // Default name: the file's stem.
    std::string stem = path.substr(path.find_last_of('/') + 1);
    c.name = stem.substr(0, stem.rfind('.'));
  }
}

// One [[vehicles.fault]]: follower, rotor, at, thrust_share (the rotor count is checked against
// the vehicle when the scene is bound, runner/sim).
ExperimentConfig::RotorFault ReadRotorFault(const Reporter& reporter, const toml::node& item,
                                            int index, const ExperimentConfig& c) {
  const toml::table* t = item.as_table();
  if (!t) reporter.Fail(&item, "[vehicles] fault", "expected [[vehicles.fault]] tables");
  SectionReader keys(reporter.path(), t, "vehicles] fault[" + std::to_string(index),
                     "vehicles.fault");
  ExperimentConfig::RotorFault f;
  f.line = static_cast<int>(item.source().begin.line);
  f.follower = static_cast<int>(keys.Integer("follower", 1));
  f.rotor = static_cast<int>(keys.Integer("rotor", 0));
  f.at = keys.Number("at", 0.0);
  f.thrust_share = keys.Number("thrust_share", 0.0);
  // Unknown keys first: a misspelt key is named as the user wrote it, not as a missing one.
  keys.RejectUnknown();
  for (const char* key : {"follower", "rotor", "at", "thrust_share"}) {
    if (!keys.Has(key)) keys.Fail(key, "missing (a fault needs follower, rotor, at, thrust_share)");
  }
  if (f.follower < 1 || f.follower > c.followers) {
    keys.Fail("follower", "must be a follower number in 1.." + std::to_string(c.followers));
  }
  if (f.rotor < 0) keys.Fail("rotor", "must be >= 0 (the attitude plugin's actuator order)");
  if (!(f.at >= 0.0 && f.at < c.duration)) {
    keys.Fail("at", "must lie in the run [0, " + fmt::format("{}", c.duration) + ") s");
  }
  if (!(f.thrust_share >= 0.0 && f.thrust_share <= 1.0)) {
    keys.Fail("thrust_share", "must be in [0, 1] (the share of the rotor's thrust lost)");
  }
  return f;
}

// A fault acts on a rotor's command: vehicles without rotor actuators are refused by name.
void ReadRotorFaults(SectionReader& vehicles, const Reporter& reporter, ExperimentConfig* c) {
  const toml::array* a = vehicles.Array("fault");
  if (!a) return;
  for (const toml::node& item : *a) {
    c->rotor_faults.push_back(
        ReadRotorFault(reporter, item, static_cast<int>(c->rotor_faults.size()) + 1, *c));
  }
  if (c->rotor_faults.empty()) return;
  if (c->model == "pointmass" || c->vehicle_actuation != VehicleActuation::kRotors) {
    vehicles.Fail("fault",
                  "a rotor fault needs a rotor vehicle (model \"quadrotor\" or a model with "
                  "rotor actuators), not the point mass or a thrust-and-moment vehicle");
  }
}

void ParseVehiclesSection(const Reporter& reporter, SectionReader vehicles, const std::string& path,
                          ExperimentConfig& c) {
  c.model = vehicles.String("model", c.model);
  c.model_path = ResolveModel(c.model, path);
  c.scene_path = ResolveModel(vehicles.String("scene", "scene"), path);
  // Range-checked before the conversion to int: 4294967297 is not 1 follower.
  const int64_t followers = vehicles.Integer("followers", c.followers);
  if (followers < 1 || followers > 100000) vehicles.Fail("followers", "must be in [1, 100000]");
  c.followers = static_cast<int>(followers);
  c.altitude = vehicles.Number("altitude", c.altitude);
  {
    auto s = vehicles.Numbers("leader_start", {c.leader_start[0], c.leader_start[1]}, 2);
    c.leader_start = {s[0], s[1]};
  }
  if (const toml::array* a = vehicles.Array("follower_start")) {
    for (const toml::node& item : *a) {
      const toml::array* xy = item.as_array();
      if (!xy || xy->size() != 2) {
        reporter.Fail(&item, "[vehicles] follower_start", "expected [[x, y], ...] in m");
      }
      c.follower_start.push_back({vehicles.AsNumber(*xy->get(0), "follower_start"),
                                  vehicles.AsNumber(*xy->get(1), "follower_start")});
    }
  }
  c.start_jitter = vehicles.Number("start_jitter", 0.0);
  c.rotor_model = vehicles.Enum("rotor_model", c.rotor_model, kRotorModelWords);
  c.contacts = vehicles.Bool("contacts", c.contacts);
  ParseVehicleMapping(vehicles, reporter, &c);
  ReadRotorFaults(vehicles, reporter, &c);
  vehicles.RejectUnknown();
  if (c.followers < 1 || c.followers > 100000) vehicles.Fail("followers", "must be in [1, 100000]");
  if (!c.follower_start.empty() && static_cast<int>(c.follower_start.size()) != c.followers) {
    vehicles.Fail("follower_start", "has " + std::to_string(c.follower_start.size()) +
                                        " entries for " + std::to_string(c.followers) +
                                        " followers");
  }
  if (c.altitude <= 0) vehicles.Fail("altitude", "must be > 0 m");
  if (c.start_jitter < 0) vehicles.Fail("start_jitter", "must be >= 0 m");
}

// [topology] edges = [[from, to(, weight)], ...] (1-based in the file, 0-based here); `label`
// names the table in messages ("[topology]", "[topology] switch[2]").
std::vector<ExperimentConfig::Edge> ReadEdges(const Reporter& reporter, SectionReader& topology,
                                              int followers, const std::string& label) {
  std::vector<ExperimentConfig::Edge> edges;
  const toml::array* a = topology.Array("edges");
  if (!a) return edges;
  for (const toml::node& item : *a) {
    const toml::array* e = item.as_array();
    if (!e || e->size() < 2 || e->size() > 3) {
      reporter.Fail(&item, label + " edges",
                    "expected [from, to] or [from, to, weight] (follower `to` receives "
                    "`from`'s state)");
    }
    auto from = e->get(0)->value_exact<int64_t>();
    auto to = e->get(1)->value_exact<int64_t>();
    if (!from || !to || *from < 1 || *to < 1 || *from > followers || *to > followers) {
      reporter.Fail(&item, label + " edges",
                    "follower numbers must be integers in 1.." + std::to_string(followers));
    }
    ExperimentConfig::Edge edge{static_cast<int>(*from - 1), static_cast<int>(*to - 1), 1.0};
    if (e->size() == 3) edge.weight = topology.AsNumber(*e->get(2), "edges");
    edges.push_back(edge);
  }
  return edges;
}

// a_i0 per follower from leader_links (weight 1) and leader_weights (overriding).
std::vector<double> ReadLeaderWeights(const Reporter& reporter, SectionReader& topology,
                                      int followers, const std::string& label) {
  std::vector<double> weight(followers, 0.0);
  if (const toml::array* a = topology.Array("leader_links")) {
    for (const toml::node& item : *a) {
      auto v = item.value_exact<int64_t>();
      if (!v || *v < 1 || *v > followers) {
        reporter.Fail(&item, label + " leader_links",
                      "expected follower numbers 1.." + std::to_string(followers));
      }
      weight[*v - 1] = 1.0;
    }
  } else if (topology.table()) {
    topology.Fail("leader_links", "missing: which followers receive the leader's state");
  }
  if (const toml::array* a = topology.Array("leader_weights")) {
    if (static_cast<int>(a->size()) != followers) {
      topology.Fail("leader_weights", "expected one weight a_i0 per follower");
    }
    for (int i = 0; i < followers; ++i) {
      weight[i] = topology.AsNumber(*a->get(i), "leader_weights");
    }
  }
  return weight;
}

// Assumption 2: every follower is reached from the leader (vertex 0) along links of positive
// weight (breadth-first search); returns the first follower (1-based) that is not, or 0.
int FollowerOffSpanningTree(const std::vector<double>& leader_weight,
                            const std::vector<ExperimentConfig::Edge>& edges) {
  const int n = static_cast<int>(leader_weight.size());
  std::vector<bool> reached(n, false);
  std::vector<int> queue;
  for (int i = 0; i < n; ++i) {
    if (leader_weight[i] > 0) {
      reached[i] = true;
      queue.push_back(i);
    }
  }
  for (size_t q = 0; q < queue.size(); ++q) {
    for (const ExperimentConfig::Edge& e : edges) {
      if (e.from == queue[q] && e.weight > 0 && !reached[e.to]) {
        reached[e.to] = true;
        queue.push_back(e.to);
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!reached[i]) return i + 1;
  }
  return 0;
}

// One [[topology.switch]]: at = s, edges and leader_links (or leader_weights) as in [topology].
ExperimentConfig::TopologySwitch ReadTopologySwitch(const Reporter& reporter,
                                                    const toml::node& item, int index,
                                                    const ExperimentConfig& c) {
  const toml::table* t = item.as_table();
  if (!t) reporter.Fail(&item, "[topology] switch", "expected [[topology.switch]] tables");
  const std::string label = "[topology] switch[" + std::to_string(index) + "]";
  SectionReader keys(reporter.path(), t, "topology] switch[" + std::to_string(index),
                     "topology.switch");
  ExperimentConfig::TopologySwitch s;
  s.line = static_cast<int>(item.source().begin.line);
  s.at = keys.Number("at", 0.0);
  s.leader_weight = ReadLeaderWeights(reporter, keys, c.followers, label);
  s.edges = ReadEdges(reporter, keys, c.followers, label);
  keys.RejectUnknown();  // before "missing": a misspelt key is named as the user wrote it
  if (!keys.Has("at")) keys.Fail("at", "missing: the time of the switch, s");
  if (!(s.at > 0.0 && s.at < c.duration)) {
    keys.Fail("at", "must lie inside the run (0, " + fmt::format("{}", c.duration) + ") s");
  }
  if (const int off = FollowerOffSpanningTree(s.leader_weight, s.edges)) {
    keys.Fail("edges",
              "this graph has no directed spanning tree rooted at the leader "
              "(Assumption 2): follower " +
                  std::to_string(off) +
                  " is not reached from the leader; every switch must keep one");
  }
  return s;
}

void ReadTopologySwitches(const Reporter& reporter, SectionReader& topology, ExperimentConfig& c) {
  const toml::array* a = topology.Array("switch");
  if (!a) return;
  for (const toml::node& item : *a) {
    c.topology_switches.push_back(
        ReadTopologySwitch(reporter, item, static_cast<int>(c.topology_switches.size()) + 1, c));
    const auto& all = c.topology_switches;
    if (all.size() > 1 && !(all.back().at > all[all.size() - 2].at)) {
      reporter.Fail(&item, "[topology] switch", "switches must be listed in increasing time (at)");
    }
  }
}

void ParseTopologySection(const Reporter& reporter, SectionReader topology, ExperimentConfig& c) {
  c.leader_weight = ReadLeaderWeights(reporter, topology, c.followers, "[topology]");
  // Generated graphs for large N: "chain" (1 -> 2 -> ... -> N) or "ring" (chain + N -> 1).
  const bool ring = topology.Enum("generate", false, kTopologyGeneratorWords);
  c.edges = ReadEdges(reporter, topology, c.followers, "[topology]");
  if (topology.Has("generate")) {
    if (!c.edges.empty()) topology.Fail("generate", "give either edges or generate, not both");
    c.edges = GeneratedEdges(c.followers, ring);
  }
  ReadTopologySwitches(reporter, topology, c);
  topology.RejectUnknown();
  if (!topology.table()) {
    // Default: the leader talks to follower 1 and the followers form a chain 1 -> 2 -> ... -> N.
    c.leader_weight[0] = 1.0;
    c.edges = GeneratedEdges(c.followers, false);
  }
}

void ParseShapeSection(const Reporter& reporter, const toml::table* formation_table,
                       const std::string& path, ExperimentConfig& c) {
  const toml::node* shape_node = formation_table ? formation_table->get("shape") : nullptr;
  if (shape_node && !shape_node->is_table()) {
    reporter.Fail(shape_node, "[formation.shape]", "expected a table");
  }
  SectionReader shape(reporter.path(), shape_node ? shape_node->as_table() : nullptr,
                      "formation.shape");
  c.shape.type =
      shape.Enum("type", shape_node ? ShapeType::kCircle : ShapeType::kNone, kShapeTypeWords);
  c.shape.radius = shape.Number("radius", c.shape.radius);
  c.shape.omega = shape.Number("omega", c.shape.omega);
  c.shape.phase0 = shape.Number("phase0", c.shape.phase0);
  c.shape.phase_step = shape.Number("phase_step", -1.0);
  c.shape.tolerance = shape.Number("tolerance", c.shape.tolerance);
  if (const toml::array* a = shape.Array("offsets")) {
    for (const toml::node& item : *a) {
      const toml::array* xy = item.as_array();
      if (!xy || xy->size() != 2) {
        reporter.Fail(&item, "[formation.shape] offsets", "expected [[x, y], ...] in m");
      }
      c.shape.offsets.push_back(
          {shape.AsNumber(*xy->get(0), "offsets"), shape.AsNumber(*xy->get(1), "offsets")});
    }
  }
  if (shape.Has("file")) c.shape.file = ResolveRelative(shape.String("file", ""), path);
  shape.MarkUsed("file");
  shape.RejectUnknown();
  const ShapeType type = c.shape.type;
  if (type == ShapeType::kCircle && c.shape.radius <= 0) shape.Fail("radius", "must be > 0 m");
  if (type == ShapeType::kOffsets && static_cast<int>(c.shape.offsets.size()) != c.followers) {
    shape.Fail("offsets", "needs one [x, y] per follower (" + std::to_string(c.followers) + ")");
  }
  if (type == ShapeType::kTable && c.shape.file.empty()) {
    shape.Fail("file",
               "type \"table\" needs file = \"shape.csv\" (t, then px, py, vx, vy per "
               "follower)");
  }
  if (c.shape.tolerance <= 0) shape.Fail("tolerance", "must be > 0 m/s");
}

void ReadRenderValues(SectionReader& render, RenderConfig& r) {
  r.snapshots = render.Numbers("snapshots", {});
  r.width = static_cast<int>(render.Integer("width", r.width));
  r.height = static_cast<int>(render.Integer("height", r.height));
  r.camera = render.Enum("camera", r.camera, kCameraModeWords);
  r.distance = render.Number("distance", r.distance);
  r.azimuth = render.Number("azimuth", r.azimuth);
  r.elevation = render.Number("elevation", r.elevation);
  {
    auto l = render.Numbers("lookat", {0, 0, 0}, 3);
    r.lookat = {l[0], l[1], l[2]};
  }
  r.shadows = render.Bool("shadows", r.shadows);
  r.trail_seconds = render.Number("trail_seconds", r.trail_seconds);
  r.video = render.Bool("video", r.video);
  r.video_fps = render.Number("video_fps", r.video_fps);
  r.video_shadows = render.Bool("video_shadows", r.video_shadows);
  r.video_width = static_cast<int>(render.Integer("video_width", r.video_width));
  r.video_height = static_cast<int>(render.Integer("video_height", r.video_height));
}

// `check_times`: snapshot times must lie inside the run (only when the run renders).
void ParseRenderSection(SectionReader render, double duration, bool check_times, RenderConfig& r) {
  ReadRenderValues(render, r);
  render.RejectUnknown();
  for (double t : r.snapshots) {
    if (t < 0 || (check_times && t > duration + 1e-9)) {
      // The usual cause is a shortened run: say which time and the two ways out.
      render.Fail("snapshots",
                  fmt::format("times must lie in [0, duration]: {} s is outside [0, {}] s (set "
                              "render.snapshots to times inside the run, e.g. [], or render "
                              "nothing: --no-render, render=False in Python)",
                              t, duration));
    }
  }
  if (r.width < 16 || r.height < 16 || r.width > 4096 || r.height > 4096) {
    render.Fail("width", "width and height must be in [16, 4096] pixels");
  }
  if (r.video_fps <= 0 || r.video_fps > 120) render.Fail("video_fps", "must be in (0, 120]");
  if (r.video_width < 16 || r.video_height < 16 || r.video_width > 4096 || r.video_height > 4096 ||
      r.video_width % 2 || r.video_height % 2) {
    render.Fail("video_width", "video size must be even and in [16, 4096] pixels");
  }
  if (r.trail_seconds < 0) render.Fail("trail_seconds", "must be >= 0 s");
}

}  // namespace

ExperimentConfig ParseExperiment(const std::string& text, const std::string& path,
                                 const std::vector<std::string>& overrides,
                                 ExperimentChecks checks) {
  Reporter reporter(path);
  toml::table root = ParseDocument(text, path, overrides);
  RejectUnknownSections(reporter, root);
  auto table_of = [&](const char* name) { return root.get_as<toml::table>(name); };

  ExperimentConfig c;
  c.source_path = path;
  c.source_text = text;
  c.overrides = overrides;
  if (!overrides.empty()) {
    std::ostringstream merged;
    merged << root;
    c.effective_text = merged.str() + "\n";
  }
  ParseRunSection(reporter, SectionReader(reporter.path(), table_of("run"), "run"), path,
                  checks.plugin_folders, c);
  ParseVehiclesSection(reporter, SectionReader(reporter.path(), table_of("vehicles"), "vehicles"),
                       path, c);
  ParseTopologySection(reporter, SectionReader(reporter.path(), table_of("topology"), "topology"),
                       c);
  c.leader = ReadPluginSection(reporter, root, "leader", kDefaultLeaderPlugin, {});
  c.formation = ReadPluginSection(reporter, root, "formation", "", {"shape"});
  c.attitude = ReadPluginSection(reporter, root, "attitude", kDefaultAttitudePlugin, {});
  c.estimator = ReadPluginSection(reporter, root, "estimator", kDefaultEstimatorPlugin, {});
  for (PluginSection* section : {&c.leader, &c.formation, &c.attitude}) {
    section->derived["seed"] = std::to_string(c.seed);
  }
  ParseShapeSection(reporter, table_of("formation"), path, c);
  ParseRenderSection(SectionReader(reporter.path(), table_of("render"), "render"), c.duration,
                     checks.render, c.render);
  ParseRealismSections(root, path, &c);  // [sensors], [wind]
  ParseNetworkSections(root, c);
  ParseSafetySections(root, path, &c);  // [safety], [run] stop_on
  return c;
}

std::string ReadExperimentText(const std::string& path) {
  // A folder opens as a stream that reads as empty, which would be refused for its first
  // missing key rather than for what it is.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw ConfigError(path + ": is a folder, not an experiment file (name a .toml file, e.g. " +
                      "experiments/exp2.toml)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open the experiment file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ExperimentConfig LoadExperiment(const std::string& path, const std::vector<std::string>& overrides,
                                ExperimentChecks checks) {
  return ParseExperiment(ReadExperimentText(path), path, overrides, checks);
}

}  // namespace mjf::runner
