// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapt/vehicle_assets.hpp"

#include <set>

#include "mjcf_util.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using mjcf::Describe;
using mjcf::IsFile;
using mjcf::Join;
using mjcf::Str;
using tinyxml2::XMLElement;

void CollectAttribute(const XMLElement* e, const char* attr, std::set<std::string>* out) {
  if (const char* v = e->Attribute(attr)) out->insert(v);
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    CollectAttribute(c, attr, out);
  }
}

// What the vehicle uses: materials, meshes and height fields named by its geoms, sites and
// defaults; textures named by the materials kept.
std::set<std::string> UsedAssets(XMLElement* root, const XMLElement* body, XMLElement* asset) {
  std::set<std::string> used;
  for (const char* attr : {"material", "mesh", "hfield"}) {
    CollectAttribute(body, attr, &used);
    if (XMLElement* d = root->FirstChildElement("default")) CollectAttribute(d, attr, &used);
  }
  for (XMLElement* a = asset->FirstChildElement("material"); a;
       a = a->NextSiblingElement("material")) {
    if (used.count(Str(a->Attribute("name")))) CollectAttribute(a, "texture", &used);
  }
  return used;
}

// Each file attribute of the kept asset `a` rewritten to the absolute path of a file that
// exists under the model's folder + `folder`.
void PointAtFiles(XMLElement* a, const std::string& folder, const std::string& model_path,
                  const std::string& dir) {
  const std::string tag = a->Name();
  for (const char* attr :
       {"file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback"}) {
    const char* file = a->Attribute(attr);
    if (!file) continue;
    const std::string path = Join(Join(dir, folder), file);
    if (!IsFile(path)) {
      throw SceneError(model_path + ":" + std::to_string(a->GetLineNum()) + ": " + Describe(a) +
                       " " + attr + "=\"" + file + "\": file not found (looked at " + path + "; " +
                       tag + " files are found relative to the model file" +
                       (folder.empty() ? ""
                                       : " and its " + std::string(tag == "texture" ? "texturedir"
                                                                                    : "meshdir")) +
                       ")");
    }
    a->SetAttribute(attr, path.c_str());
  }
}

}  // namespace

std::vector<std::string> ResolveAssets(XMLElement* root, const XMLElement* body,
                                       const std::string& model_path, const std::string& dir,
                                       std::vector<std::string> notes) {
  auto Note = [&notes](const std::string& s) { notes.push_back(s); };
  std::string meshdir, texturedir;
  if (XMLElement* c = root->FirstChildElement("compiler")) {
    const std::string assetdir = Str(c->Attribute("assetdir"));
    meshdir = c->Attribute("meshdir") ? Str(c->Attribute("meshdir")) : assetdir;
    texturedir = c->Attribute("texturedir") ? Str(c->Attribute("texturedir")) : assetdir;
    for (const char* a : {"assetdir", "meshdir", "texturedir"}) c->DeleteAttribute(a);
  }
  XMLElement* asset = root->FirstChildElement("asset");
  if (!asset) return notes;
  const std::set<std::string> used = UsedAssets(root, body, asset);
  std::string unused;
  for (XMLElement* a = asset->FirstChildElement(); a;) {
    XMLElement* next = a->NextSiblingElement();
    const std::string tag = a->Name();
    // Meshes may be named after their file (MuJoCo's default name: the file's stem).
    std::string name = Str(a->Attribute("name"));
    if (name.empty() && a->Attribute("file")) {
      name = Str(a->Attribute("file"));
      name = name.substr(name.find_last_of('/') + 1);
      name = name.substr(0, name.rfind('.'));
    }
    if (tag == "texture" && a->Attribute("type", "skybox")) {
      Note("dropped " + Describe(a) + " (line " + std::to_string(a->GetLineNum()) +
           "): the sky is the scene's");
      asset->DeleteChild(a);
    } else if (!used.count(name)) {
      unused += (unused.empty() ? "" : ", ") + tag + " '" + name + "'";
      asset->DeleteChild(a);
    } else {
      PointAtFiles(a, tag == "texture" ? texturedir : meshdir, model_path, dir);
    }
    a = next;
  }
  if (!unused.empty()) Note("dropped assets the vehicle does not use: " + unused);
  return notes;
}

}  // namespace mjf::runner
