// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "bundle.hpp"

#include <mujoco/mujoco.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "mjformation/export/export.hpp"
#include "mjformation/export/scene_anchor.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;

// A 1 x 1 white PNG: the anchor's file (any image MuJoCo decodes would do; this is the smallest).
constexpr unsigned char kAnchorPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
    0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9c, 0x63, 0xf8, 0xff, 0xff, 0x3f, 0x00, 0x05, 0xfe, 0x02, 0xfe, 0x0d, 0xef, 0x46,
    0xb8, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
// Where the copies of the anchor's bytes come from in copies_ (no file on disk).
constexpr char kAnchorSource[] = "";

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ExportError(path + ": cannot read it: " + std::strerror(errno));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  if (!out) throw ExportError(path.string() + ": cannot write it: " + std::strerror(errno));
}

// The resolved path of every asset file a compiled model names (meshes, skins, height fields,
// textures): MuJoCo keeps them in mjModel::paths.
std::vector<std::string> AssetPaths(const mjModel* m) {
  std::vector<std::string> paths;
  auto add = [&](const int* adr, int n) {
    for (int i = 0; i < n; ++i) {
      if (adr[i] >= 0) paths.emplace_back(m->paths + adr[i]);
    }
  };
  add(m->mesh_pathadr, m->nmesh);
  add(m->skin_pathadr, m->nskin);
  add(m->hfield_pathadr, m->nhfield);
  add(m->tex_pathadr, m->ntex);
  return paths;
}

fs::path Absolute(const std::string& path) { return fs::absolute(path).lexically_normal(); }

// The manifest's first line: a folder whose manifest starts with it was written by export.
constexpr char kManifestHeader[] =
    "# written by mjformation export; --overwrite replaces scene.xml and these only";

// What export wrote into `out_dir` before, as relative names: the manifest, scene.xml (which the
// manifest's header names) and the files it lists; nothing when the folder holds no manifest of
// export's.
std::set<std::string> WrittenBefore(const fs::path& out_dir) {
  std::ifstream in(out_dir / SceneBundle::kManifest);
  std::string line;
  if (!std::getline(in, line) || line != kManifestHeader) return {};
  std::set<std::string> written = {SceneBundle::kManifest, "scene.xml"};
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#') written.insert(line);
  }
  return written;
}

}  // namespace

SceneBundle::SceneBundle(std::string out_dir) : out_dir_(std::move(out_dir)) {
  copies_[kSceneAnchorFile] = kAnchorSource;
}

std::string SceneBundle::Add(const std::string& source, const std::string& relative) {
  std::string name = relative;
  for (int n = 2;; ++n) {
    auto [it, inserted] = copies_.emplace(name, source);
    if (inserted || it->second == source) return name;
    const fs::path p(relative);
    name = (p.parent_path() / (std::to_string(n) + "_" + p.filename().string())).string();
  }
}

std::string SceneBundle::AddModel(const std::string& model_path, const std::string& folder) {
  // An <include>d file is not among the compiled model's paths: the copy would not load.
  if (ReadBytes(model_path).find("<include") != std::string::npos) {
    throw ExportError(model_path +
                      ": includes other MJCF files (<include>), which export does "
                      "not carry; merge them into the model file to export it");
  }
  char error[1024] = {0};
  mjModel* m = mj_loadXML(model_path.c_str(), nullptr, error, sizeof(error));
  if (!m) throw ExportError(model_path + ": MuJoCo cannot load it: " + error);
  const std::vector<std::string> assets = AssetPaths(m);
  mj_deleteModel(m);
  const fs::path dir = Absolute(model_path).parent_path();
  const fs::path name = Absolute(model_path).filename();
  // A folder of its own: the model's asset files keep their places relative to it.
  const std::string home = Add(Absolute(model_path).string(), folder + "/" + name.string());
  const fs::path home_dir = fs::path(home).parent_path();
  for (const std::string& asset : assets) {
    const fs::path relative = Absolute(asset).lexically_relative(dir);
    if (relative.empty() || *relative.begin() == "..") {
      throw ExportError(model_path + ": asset file " + asset +
                        " lies outside the model's folder; export carries the asset files "
                        "below a model's folder only: move it there (and name it from there)");
    }
    if (Add(Absolute(asset).string(), (home_dir / relative).string()) !=
        (home_dir / relative).string()) {
      throw ExportError(model_path + ": asset file " + asset +
                        " would be written over another "
                        "model's file of the same name in the exported folder");
    }
  }
  return home;
}

void SceneBundle::Relocate(toml::table& doc, const ExperimentConfig& config,
                           std::vector<std::string>* notes) {
  if (!doc.contains("vehicles")) doc.insert("vehicles", toml::table{});
  toml::table& vehicles = *doc["vehicles"].as_table();
  vehicles.insert_or_assign("model", AddModel(config.model_path, "vehicle"));
  vehicles.insert_or_assign("scene", AddModel(config.scene_path, "world"));
  auto relocate_file = [&](toml::table* table) {
    if (!table) return;
    if (auto file = table->get_as<std::string>("file")) {
      const fs::path source = Absolute(file->get());
      table->insert_or_assign("file", Add(source.string(), "data/" + source.filename().string()));
    }
  };
  for (const char* section : {"leader", "formation", "attitude", "estimator"}) {
    relocate_file(doc[section].as_table());
  }
  relocate_file(doc["formation"]["shape"].as_table());
  if (const toml::array* folders = doc["run"]["plugin_path"].as_array()) {
    // Absolute: the plugin reads a relative folder against the scene's folder (a --plugin-path
    // given relative to the working folder is not there).
    toml::array absolute;
    for (const toml::node& folder : *folders) {
      const auto text = folder.value_exact<std::string>();
      absolute.push_back(text ? Absolute(*text).string() : std::string());
    }
    doc["run"].as_table()->insert_or_assign("plugin_path", std::move(absolute));
  }
  if (notes && doc.at_path("run.plugin_path").as_array()) {
    notes->push_back(
        "[run] plugin_path names folders of this machine (their libraries are not copied): the "
        "scene flies elsewhere with the plugins found beside libmjformation_mujoco.so or in its "
        "installed prefix");
  }
}

std::string SceneBundle::Relocated(std::string xml) {
  // The composed scene names its asset files by absolute paths (the composition resolved them),
  // so the compiler's meshdir, texturedir and assetdir are inert in it; once the names are
  // relative they would move them, so they go.
  const size_t compiler = xml.find("<compiler ");
  const size_t compiler_end = compiler == std::string::npos ? compiler : xml.find('>', compiler);
  for (const char* dir : {" meshdir=\"", " texturedir=\"", " assetdir=\""}) {
    const size_t at = xml.find(dir, compiler);
    if (at == std::string::npos || at > compiler_end) continue;
    const size_t close = xml.find('"', at + std::strlen(dir));
    xml.erase(at, close + 1 - at);
  }
  // Each asset file: the copy already made for a model (a vehicle's mesh), else one in assets/.
  std::map<std::string, std::string> copied;  // source -> relative name
  for (const auto& [relative, source] : copies_) copied.emplace(source, relative);
  const std::string key = " file=\"";
  for (size_t at = xml.find(key); at != std::string::npos; at = xml.find(key, at + 1)) {
    const size_t begin = at + key.size();
    const size_t end = xml.find('"', begin);
    const std::string file = xml.substr(begin, end - begin);
    if (file.empty() || file[0] != '/') {
      throw ExportError("the composed scene names the asset file '" + file +
                        "' by a relative path; export cannot tell where it lies");
    }
    const std::string source = Absolute(file).string();
    const auto found = copied.find(source);
    const std::string relative = found != copied.end()
                                     ? found->second
                                     : Add(source, "assets/" + fs::path(file).filename().string());
    xml.replace(begin, end - begin, relative);
  }
  const size_t asset = xml.find("<asset>");
  const std::string anchor = std::string("    <texture name=\"") + kSceneAnchorTexture +
                             "\" type=\"2d\" file=\"" + kSceneAnchorFile + "\"/>\n";
  if (asset != std::string::npos) {
    xml.insert(xml.find('\n', asset) + 1, anchor);
  } else {
    const size_t worldbody = xml.find("  <worldbody>");
    if (worldbody == std::string::npos) throw ExportError("the composed scene has no <worldbody>");
    xml.insert(worldbody, "  <asset>\n" + anchor + "  </asset>\n\n");
  }
  return xml;
}

void SceneBundle::Write(const std::string& scene_xml) const {
  const fs::path out(out_dir_);
  const std::set<std::string> written_before = WrittenBefore(out);
  std::vector<std::pair<std::string, std::string>> files;  // relative name, bytes
  std::string manifest = std::string(kManifestHeader) + "\n";
  for (const auto& [relative, source] : copies_) {
    files.emplace_back(relative, source == kAnchorSource
                                     ? std::string(std::begin(kAnchorPng), std::end(kAnchorPng))
                                     : ReadBytes(source));
    manifest += relative + "\n";
  }
  files.emplace_back("scene.xml", scene_xml);
  files.emplace_back(kManifest, manifest);  // last: the folder is export's once it is there
  // Refusals first: nothing is written when one file would be lost.
  for (const auto& [relative, bytes] : files) {
    std::error_code ec;
    const fs::path target = out / relative;
    if (!fs::exists(target, ec) || written_before.count(relative)) continue;
    if (!fs::is_regular_file(target, ec) || ReadBytes(target.string()) != bytes) {
      throw ExportError(target.string() + ": exists and was not written by export; move it " +
                        "away or export into another folder");
    }
  }
  for (const auto& [relative, bytes] : files) WriteBytes(out / relative, bytes);
}

}  // namespace mjf::runner
