// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/export/export.hpp"

#include <sys/stat.h>
#include <toml++/toml.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "bundle.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/config/overrides.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/stages.hpp"
#include "mjformation/export/carried_sections.hpp"
#include "mjformation/export/scene_anchor.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;

// Sections that change what is recorded or drawn, never the flight: not carried, and said so,
// each with why.
const std::map<std::string, std::string>& OutputOnlySections() {
  static const std::map<std::string, std::string> kOutput = {
      {"render",
       "it shapes the runner's images, not the flight (MuJoCo's own viewer renders the exported "
       "scene)"},
      {"safety",
       "safety events (flips, ground impacts, collisions, near misses, leaving the region) are "
       "recorded by the runner only; the exported scene flies the same flight and records "
       "nothing"},
  };
  return kOutput;
}

// "[run], [vehicles], ... and [wind]": what the native plugins carry, for a refusal.
std::string CarriedList() {
  std::string list;
  const std::vector<std::string>& carried = CarriedSections();
  for (size_t i = 0; i < carried.size(); ++i) {
    list += std::string(i == 0                    ? ""
                        : i + 1 == carried.size() ? " and "
                                                  : ", ") +
            "[" + carried[i] + "]";
  }
  return list;
}

std::string Quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof(escape), "\\u%04x", c);
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string Key(std::string_view key) {
  bool bare = !key.empty();
  for (char c : key)
    bare = bare && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
  return bare ? std::string(key) : Quoted(key);
}

// One TOML value on one line, floats in their shortest form that reads back to the same double.
std::string Value(const toml::node& node) {
  if (const toml::table* t = node.as_table()) {
    std::string out = "{";
    for (auto&& [key, value] : *t) {
      out += (out.size() > 1 ? ", " : " ") + Key(key.str()) + " = " + Value(value);
    }
    return out + (out.size() > 1 ? " }" : "}");
  }
  if (const toml::array* a = node.as_array()) {
    std::string out = "[";
    for (size_t i = 0; i < a->size(); ++i) out += (i ? ", " : "") + Value(*a->get(i));
    return out + "]";
  }
  if (auto v = node.value_exact<std::string>()) return Quoted(*v);
  if (auto v = node.value_exact<int64_t>()) return std::to_string(*v);
  if (auto v = node.value_exact<bool>()) return *v ? "true" : "false";
  if (auto v = node.value_exact<double>()) {
    if (std::isnan(*v)) return "nan";
    if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), *v);
    std::string text(buffer, ec == std::errc() ? end : buffer);
    if (text.find_first_of(".eE") == std::string::npos) text += ".0";  // stays a float
    return text;
  }
  // Dates and times: no experiment key takes one, and the parser names it.
  throw ExportError("a date or time value where the experiment file takes none (line " +
                    std::to_string(node.source().begin.line) + ")");
}

// The section as the body of a TOML inline table: `radius = 20.0, omega = 0.157`.
std::string InlineBody(const toml::table& section) {
  std::string out;
  for (auto&& [key, value] : section) {
    out += (out.empty() ? "" : ", ") + Key(key.str()) + " = " + Value(value);
  }
  return out;
}

std::string XmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '"':
        out += "&quot;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// The wrench rotor model's one actuator (AddTickActuator).
constexpr char kTickActuator[] = "mjformation_swarm_tick";

// The plugin declaration: one instance flies every vehicle of the scene. The comment above it is
// for whoever opens the scene without our library loaded: MuJoCo then stops at this element with
// "plugin mjformation.swarm not found", which does not say where the plugin comes from.
std::string ExtensionBlock(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::string xml =
      "  <!-- Flown by mjformation's native MuJoCo plugins: load libmjformation_mujoco.so before\n"
      "       compiling this scene. Python: `import mjformation` (then "
      "mujoco.MjModel.from_xml_path\n"
      "       flies it); a pip-installed mjformation loads it with `import mujoco`; C:\n"
      "       mj_loadPluginLibrary(\"PATH/libmjformation_mujoco.so\"). Keep the files beside this\n"
      "       scene: it names them by relative paths. -->\n"
      "  <extension>\n    <plugin plugin=\"mjformation.swarm\">\n"
      "      <instance name=\"" +
      std::string(kSwarmInstance) + "\">\n";
  for (const auto& [key, value] : pairs) {
    xml += "        <config key=\"" + key + "\" value=\"" + XmlEscape(value) + "\"/>\n";
  }
  xml += "      </instance>\n    </plugin>\n  </extension>\n";
  return xml;
}

// Every vehicle's body references the swarm instance (`<plugin instance="swarm"/>` as its first
// child). MuJoCo's attach (mjs_attach, Python's MjSpec.attach) copies only the instances that an
// element of the attached tree references: an instance declared in <extension> alone is dropped
// and the drones would fall without a controller. The references also tell the plugin the
// prefix and suffix an attach gave the names (mujoco_plugin/src/attach_names.hpp). They change
// nothing in the physics: the plugin adds no passive force.
void ReferenceInstanceFromVehicles(std::string* xml, int vehicles) {
  size_t from = 0;  // the vehicles come in index order: each search starts at the one before
  for (int i = 0; i < vehicles; ++i) {
    const std::string open = "<body name=\"" + VehiclePrefix(i) + "vehicle\"";
    size_t at = xml->find(open, from);
    if (at == std::string::npos) at = xml->find(open);
    from = at;
    const size_t end = at == std::string::npos ? at : xml->find('>', at);
    if (end == std::string::npos || (*xml)[end - 1] == '/') {
      throw ExportError("the composed scene has no body '" + VehiclePrefix(i) +
                        "vehicle' with children, which the swarm instance flies");
    }
    // The indentation of the body's first child, so the scene reads as MuJoCo writes it.
    const size_t line = end + 1;
    const size_t text = xml->find_first_not_of(" \t", line + 1);
    const std::string indent = xml->substr(line + 1, text - line - 1);
    xml->insert(line + 1, indent + "<plugin instance=\"swarm\"/>\n");
  }
}

// The wrench rotor model's scene has no actuator (the runner strips the rotors' and adds their
// wrenches itself), and MuJoCo calls an actuator plugin only in a model with an actuator
// (mj_fwdActuation returns when nu = 0): one actuator of no force (gear 0) on the leader's joint
// lets the swarm instance tick and add the wrenches. Its force is +0, and so is every entry of
// qfrc_actuator, as in the runner's scene without actuators: the same sums, the same bits.
void AddTickActuator(std::string* xml, const mjModel* m) {
  const std::string leader = VehiclePrefix(0) + "vehicle";
  const int body = mj_name2id(m, mjOBJ_BODY, leader.c_str());
  const int joint = body < 0 || m->body_jntnum[body] == 0 ? -1 : m->body_jntadr[body];
  const char* name = joint < 0 ? nullptr : mj_id2name(m, mjOBJ_JOINT, joint);
  const size_t end = xml->rfind("</mujoco>");
  if (!name || end == std::string::npos) {
    throw ExportError("the composed scene's body '" + leader +
                      "' has no named joint for the wrench rotor model's tick actuator");
  }
  xml->insert(end, std::string("  <actuator>\n    <general name=\"") + kTickActuator +
                       "\" joint=\"" + XmlEscape(name) + "\" gear=\"0 0 0 0 0 0\"/>\n" +
                       "  </actuator>\n");
}

std::string Where(const std::string& file, const toml::node& node, const std::string& key) {
  const toml::source_region& r = node.source();
  return file + ":" + std::to_string(r.begin.line) + ": [" + key + "]";
}

// Paths resolved: the runner reads them relative to the experiment file. The scene text alone
// keeps them so (it has no folder); the exported folder's copies are named relative to the scene
// (SceneBundle::Relocate), which the native plugin finds by the scene's anchor.
void ResolvePaths(toml::table& doc, const std::string& file, const ExperimentConfig& config) {
  if (!config.plugin_path.empty()) {
    toml::array folders;
    for (const std::string& folder : config.plugin_path) folders.push_back(folder);
    if (!doc.contains("run")) doc.insert("run", toml::table{});
    doc["run"].as_table()->insert_or_assign("plugin_path", std::move(folders));
  }
  if (toml::table* vehicles = doc["vehicles"].as_table(); vehicles && vehicles->contains("model")) {
    vehicles->insert_or_assign("model", config.model_path);
  }
  // A plugin's `file` attribute ([leader] file = "path.csv") and the shape table.
  auto resolve_file = [&](toml::table* table) {
    if (!table) return;
    if (auto name = table->get_as<std::string>("file")) {
      table->insert_or_assign("file", ResolveRelative(name->get(), file));
    }
  };
  for (const char* section : {"leader", "formation", "attitude", "estimator"}) {
    resolve_file(doc[section].as_table());
  }
  resolve_file(doc["formation"]["shape"].as_table());
}

// The experiment file's document with the overrides applied, as LoadExperiment reads it.
toml::table ExperimentTable(const std::string& file, const std::vector<std::string>& overrides) {
  toml::table doc;
  try {
    doc = toml::parse(ReadExperimentText(file), file);
  } catch (const toml::parse_error& e) {
    throw ConfigError(file + ":" + std::to_string(e.source().begin.line) + ":" +
                      std::to_string(e.source().begin.column) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  ApplyOverrides(doc, overrides);
  return doc;
}

// A run that stops at a safety event has no counterpart in a scene: MuJoCo's stepping goes on
// whatever the plugin reports, so the scene would fly on where the run ended.
void RefuseStopOn(const std::string& file, const toml::table& doc) {
  const toml::node* stop_on = doc.at_path("run.stop_on").node();
  const toml::array* events = stop_on ? stop_on->as_array() : nullptr;
  if (events && !events->empty()) {
    throw ExportError(Where(file, *stop_on, "run") +
                      " stop_on: not carried by the native MuJoCo plugins (nothing ends "
                      "MuJoCo's stepping at a safety event); export with --set "
                      "'run.stop_on=[]' or fly it with `mjformation run`");
  }
}

// The native plugin's state has a length fixed when MuJoCo compiles the scene, and it bounds
// what would grow with the configuration (a latency buffer): refused here, naming the key and the
// number, rather than when MuJoCo loads the scene.
void RefuseUnboundedState(const std::string& file, const toml::table& doc,
                          const ExperimentConfig& config) {
  const std::string sensors_why = NativeSensorRefusal(config);
  const std::string why =
      !sensors_why.empty() ? sensors_why : NativeNetworkRefusal(config.network, config.timestep);
  if (why.empty()) return;
  const toml::node* section = doc.get(sensors_why.empty() ? "network" : "sensors");
  const int line = section ? static_cast<int>(section->source().begin.line) : 0;
  throw ExportError(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + why);
}

// Reads the experiment file's sections, refusing what the native path cannot carry. `config`
// is null for the refusal pass. With a `bundle`, the paths are those of the exported folder.
std::vector<std::pair<std::string, std::string>> CarriedPairs(
    const std::string& file, const std::vector<std::string>& overrides,
    const ExperimentConfig* config, std::vector<std::string>* notes,
    SceneBundle* bundle = nullptr) {
  toml::table doc = ExperimentTable(file, overrides);
  RefuseStopOn(file, doc);
  if (config) {
    RefuseUnboundedState(file, doc, *config);
    ResolvePaths(doc, file, *config);
    if (bundle) bundle->Relocate(doc, *config, notes);
  }
  std::vector<std::pair<std::string, std::string>> pairs;
  for (auto&& [key, node] : doc) {
    const std::string section(key.str());
    const auto output_only = OutputOnlySections().find(section);
    if (output_only != OutputOnlySections().end()) {
      if (notes) notes->push_back("[" + section + "] is not carried: " + output_only->second);
      continue;
    }
    bool known = false;
    for (const std::string& carried : CarriedSections()) known = known || section == carried;
    if (!known) {
      throw ExportError(Where(file, node, section) + ": the native MuJoCo plugins carry " +
                        CarriedList() +
                        " (and note [render] and [safety], the runner's outputs), not this " +
                        "section: run it with `mjformation run`");
    }
  }
  for (const std::string& carried : CarriedSections()) {
    const toml::table* section = doc[carried].as_table();
    pairs.emplace_back(carried, section ? InlineBody(*section) : "");
  }
  return pairs;
}

bool NonEmptyDirectory(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return false;
  if (!fs::is_directory(dir, ec)) return true;
  return fs::directory_iterator(dir, ec) != fs::directory_iterator();
}

// The composed scene with the plugin declared; with a `bundle`, the scene of the exported folder
// (relative paths, the anchor) and the files to copy recorded in it.
std::string SceneXml(const std::string& experiment, const ExportOptions& options,
                     std::vector<std::string>* notes, SceneBundle* bundle) {
  // The file as `run` reads it first (an unknown section or a bad value is worded as there),
  // then what the native path cannot carry, before anything is composed.
  ExperimentConfig config =
      LoadExperiment(experiment, options.overrides, ExperimentChecks::Rendering(false));
  CarriedPairs(experiment, options.overrides, nullptr, nullptr);
  for (const std::string& folder : options.plugin_path) config.plugin_path.push_back(folder);
  const std::vector<std::pair<std::string, std::string>> pairs =
      CarriedPairs(experiment, options.overrides, &config, notes, bundle);
  // The scene the runner composes for this experiment, vehicles, leader and all.
  Simulation simulation(config);
  std::string xml = simulation.scene_xml();
  if (bundle) xml = bundle->Relocated(std::move(xml));
  const size_t open = xml.find("<mujoco");
  const size_t end = open == std::string::npos ? open : xml.find('>', open);
  if (end == std::string::npos) throw ExportError("the composed scene has no <mujoco> element");
  xml.insert(end + 2, ExtensionBlock(pairs));
  ReferenceInstanceFromVehicles(&xml, config.followers + 1);
  if (config.rotor_model == RotorModel::kWrench) AddTickActuator(&xml, simulation.model());
  return xml;
}

}  // namespace

std::string ExportedSceneXml(const std::string& experiment, const ExportOptions& options,
                             std::vector<std::string>* notes) {
  return SceneXml(experiment, options, notes, nullptr);
}

ExportResult ExportExperiment(const std::string& experiment, const std::string& out_dir,
                              const ExportOptions& options) {
  std::error_code ec;
  if (fs::exists(out_dir, ec) && !fs::is_directory(out_dir, ec)) {
    throw ExportError(out_dir + ": is a file, not a folder; export writes a folder (scene.xml " +
                      "and the files it needs): name a folder that is new or empty");
  }
  if (NonEmptyDirectory(out_dir) && !options.overwrite) {
    throw ExportError(out_dir + ": exists and is not empty; pass --overwrite (Python: " +
                      "overwrite=True) to replace scene.xml and the files export wrote in it");
  }
  ExportResult result;
  SceneBundle bundle(out_dir);
  const std::string xml = SceneXml(experiment, options, &result.notes, &bundle);
  fs::create_directories(out_dir, ec);
  if (ec) throw ExportError(out_dir + ": cannot create it: " + ec.message());
  result.scene_path = (fs::path(out_dir) / "scene.xml").string();
  bundle.Write(xml);
  return result;
}

}  // namespace mjf::runner
