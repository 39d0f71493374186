// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/export/export.hpp"

#include <sys/stat.h>
#include <toml++/toml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "mjformation/config/config.hpp"
#include "mjformation/sim/simulation.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;

// What the native plugin carries: these sections (each as one <config> key, see
// mujoco_plugin/src/swarm_host.hpp), each without the keys listed against it.
struct Carried {
  const char* section;
  std::set<std::string> refused;  // keys the native path cannot carry
  const char* why;
};

const std::vector<Carried>& CarriedSections() {
  static const std::vector<Carried> kCarried = {
      {"run", {}, ""},
      {"vehicles",
       {"rotor_model", "body", "rotors", "thrust", "moments", "actuation"},
       "the native plugin drives the vehicle model's own MuJoCo actuators, as written"},
      {"topology", {}, ""},
      {"leader", {}, ""},
      {"formation", {}, ""},
      {"attitude", {}, ""},
  };
  return kCarried;
}

// Sections that change what is recorded or drawn, never the flight: not carried, and said so.
const std::set<std::string>& OutputOnlySections() {
  static const std::set<std::string> kOutput = {"render"};
  return kOutput;
}

// Flags every table inline, so a section prints as one line.
void MakeInline(toml::table& table) {
  table.is_inline(true);
  for (auto&& [key, node] : table) {
    if (toml::table* sub = node.as_table()) MakeInline(*sub);
  }
}

// The section as the body of a TOML inline table: `radius = 20.0, omega = 0.157`.
std::string InlineBody(const toml::table& section) {
  toml::table copy = section;
  MakeInline(copy);
  std::ostringstream out;
  out << toml::toml_formatter(copy, toml::format_flags::none);
  std::string text = out.str();
  for (char& ch : text) ch = ch == '\n' ? ' ' : ch;  // one line: XML would fold it anyway
  // The formatter writes `{ ... }`; the braces are the plugin's to add.
  const size_t open = text.find('{');
  const size_t close = text.rfind('}');
  if (open == std::string::npos || close == std::string::npos || close < open) return text;
  std::string body = text.substr(open + 1, close - open - 1);
  while (!body.empty() && body.front() == ' ') body.erase(body.begin());
  while (!body.empty() && body.back() == ' ') body.pop_back();
  return body;
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

// The plugin declaration: one instance flies every vehicle of the scene.
std::string ExtensionBlock(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::string xml =
      "  <extension>\n    <plugin plugin=\"mjformation.swarm\">\n"
      "      <instance name=\"swarm\">\n";
  for (const auto& [key, value] : pairs) {
    xml += "        <config key=\"" + key + "\" value=\"" + XmlEscape(value) + "\"/>\n";
  }
  xml += "      </instance>\n    </plugin>\n  </extension>\n";
  return xml;
}

std::string Where(const std::string& file, const toml::node& node, const std::string& key) {
  const toml::source_region& r = node.source();
  return file + ":" + std::to_string(r.begin.line) + ": [" + key + "]";
}

// Reads the experiment file's sections, refusing what the native path cannot carry.
std::vector<std::pair<std::string, std::string>> CarriedPairs(const std::string& file,
                                                              std::vector<std::string>* notes) {
  toml::table doc;
  try {
    doc = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw ConfigError(file + ": " + std::string(e.description()));
  }
  std::vector<std::pair<std::string, std::string>> pairs;
  for (auto&& [key, node] : doc) {
    const std::string section(key.str());
    if (OutputOnlySections().count(section)) {
      notes->push_back("[" + section + "] is not carried: it shapes the runner's images, not " +
                       "the flight (MuJoCo's own viewer renders the exported scene)");
      continue;
    }
    bool known = false;
    for (const Carried& c : CarriedSections()) known = known || section == c.section;
    if (!known) {
      throw ExportError(Where(file, node, section) +
                        ": the native MuJoCo plugins cannot carry this section (they fly the " +
                        "ideal configuration: central execution, true sensor values, no " +
                        "estimator, no wind or disturbance); run it with `mjformation run`");
    }
  }
  for (const Carried& c : CarriedSections()) {
    const toml::table* section = doc[c.section].as_table();
    if (!section) {
      pairs.emplace_back(c.section, "");
      continue;
    }
    for (auto&& [key, node] : *section) {
      if (c.refused.count(std::string(key.str()))) {
        throw ExportError(Where(file, node, std::string(c.section)) + " " + std::string(key.str()) +
                          ": not carried by the native MuJoCo " + "plugins (" + c.why + ")");
      }
    }
    pairs.emplace_back(c.section, InlineBody(*section));
  }
  return pairs;
}

bool NonEmptyDirectory(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return false;
  if (!fs::is_directory(dir, ec)) return true;
  return fs::directory_iterator(dir, ec) != fs::directory_iterator();
}

}  // namespace

std::string ExportedSceneXml(const std::string& experiment, std::vector<std::string>* notes) {
  std::vector<std::pair<std::string, std::string>> pairs = CarriedPairs(experiment, notes);
  const ExperimentConfig config =
      LoadExperiment(experiment, {}, ExperimentChecks::Rendering(false));
  // The scene the runner composes for this experiment, vehicles, leader and all.
  Simulation simulation(config);
  std::string xml = simulation.scene_xml();
  const size_t open = xml.find("<mujoco");
  const size_t end = open == std::string::npos ? open : xml.find('>', open);
  if (end == std::string::npos) throw ExportError("the composed scene has no <mujoco> element");
  xml.insert(end + 2, ExtensionBlock(pairs));
  return xml;
}

ExportResult ExportExperiment(const std::string& experiment, const std::string& out_dir,
                              bool overwrite) {
  if (NonEmptyDirectory(out_dir) && !overwrite) {
    throw ExportError(out_dir + ": exists and is not empty; pass --overwrite to replace " +
                      "scene.xml in it");
  }
  ExportResult result;
  const std::string xml = ExportedSceneXml(experiment, &result.notes);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw ExportError(out_dir + ": cannot create it: " + ec.message());
  result.scene_path = (fs::path(out_dir) / "scene.xml").string();
  std::ofstream out(result.scene_path, std::ios::binary);
  out << xml;
  if (!out) throw ExportError(result.scene_path + ": cannot write it: " + std::strerror(errno));
  return result;
}

}  // namespace mjf::runner
