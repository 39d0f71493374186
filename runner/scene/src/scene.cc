// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/scene.hpp"

#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>

#include "mjcf_util.hpp"

namespace mjf::runner {
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

void Load(XMLDocument& doc, const std::string& path, const char* what) {
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw SceneError(path + ":" + std::to_string(doc.ErrorLineNum()) + ": cannot read the " + what +
                     ": " + doc.ErrorStr());
  }
  if (!doc.RootElement() || std::strcmp(doc.RootElement()->Name(), "mujoco") != 0) {
    throw SceneError(path + ": the " + std::string(what) + " is not MJCF (no <mujoco> root)");
  }
}

XMLElement* ChildOrNew(XMLDocument& doc, XMLElement* parent, const char* tag) {
  XMLElement* e = parent->FirstChildElement(tag);
  if (!e) e = parent->InsertNewChildElement(tag);
  (void)doc;
  return e;
}

void CopyAttributes(const XMLElement* from, XMLElement* to) {
  for (auto* a = from->FirstAttribute(); a; a = a->Next()) to->SetAttribute(a->Name(), a->Value());
}

void PrefixNames(XMLElement* e, const std::string& prefix) {
  // The element's own name and every name it refers to belong to this copy.
  if (const char* v = e->Attribute("name")) e->SetAttribute("name", (prefix + v).c_str());
  for (const auto& ref : mjcf::kReferenceAttributes) {
    if (const char* v = e->Attribute(ref.name)) e->SetAttribute(ref.name, (prefix + v).c_str());
  }
  for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    PrefixNames(c, prefix);
  }
}

std::string FormatVec(const std::array<double, 3>& v) {
  char buf[128];
  std::snprintf(buf, sizeof(buf), "%.17g %.17g %.17g", v[0], v[1], v[2]);
  return buf;
}

// Bring your own quadrotor: what the adapter did to the model, for the scene's header comment.
std::string AdapterNotes(const SceneRequest& request) {
  if (request.vehicle_xml.empty()) return "";
  std::string out = ",\n  adapted to the vehicle contract (docs/VEHICLES.md):";
  for (std::string n : request.vehicle_notes) {
    for (size_t k; (k = n.find("--")) != std::string::npos;) n.replace(k, 2, "-");  // XML comment
    out += "\n    " + n;
  }
  return out + "\n";
}

}  // namespace

std::string VehiclePrefix(int vehicle) { return "uav" + std::to_string(vehicle) + "_"; }

namespace {

// The vehicle's top-level body: exactly one, named "vehicle".
const XMLElement* VehicleBody(const XMLElement* vroot, const std::string& vehicle_path) {
  const XMLElement* vworld = vroot->FirstChildElement("worldbody");
  const XMLElement* body = nullptr;
  for (const XMLElement* b = vworld ? vworld->FirstChildElement("body") : nullptr; b;
       b = b->NextSiblingElement("body")) {
    if (b->Attribute("name", "vehicle")) {
      if (body) throw SceneError(vehicle_path + ": two top-level bodies named 'vehicle'");
      body = b;
    }
  }
  if (!body) {
    throw SceneError(vehicle_path +
                     ": no top-level <body name=\"vehicle\"> in <worldbody> (see "
                     "docs/ARCHITECTURE.md, vehicle model contract)");
  }
  return body;
}

// <default> or <asset> of the vehicle added to the scene's, skipping names it already has; asset
// files are found relative to the vehicle file, wherever the scene is written.
void MergeNamedChildren(XMLDocument& scene, XMLElement* root, const XMLElement* s,
                        const std::string& vdir) {
  const std::string tag = s->Name();
  XMLElement* target = ChildOrNew(scene, root, tag.c_str());
  if (tag == "default") CopyAttributes(s, target);
  std::set<std::string> existing;
  for (XMLElement* c = target->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (const char* n = c->Attribute("name")) existing.insert(std::string(c->Name()) + n);
    if (const char* n = c->Attribute("class")) existing.insert(std::string(c->Name()) + n);
  }
  for (const XMLElement* c = s->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const char* n = c->Attribute(tag == "default" ? "class" : "name");
    if (n && existing.count(std::string(c->Name()) + n)) continue;
    XMLElement* copy = c->DeepClone(&scene)->ToElement();
    if (const char* file = copy->Attribute("file"); file && file[0] != '/') {
      copy->SetAttribute("file", (vdir + "/" + file).c_str());
    }
    target->InsertEndChild(copy);
  }
}

// Global sections: the vehicle's compiler, option, size, default and asset merged into the scene.
void MergeGlobalSections(XMLDocument& scene, XMLElement* root, const XMLElement* vroot,
                         const std::string& vehicle_path) {
  const std::string vdir = mjcf::ModelDirectory(vehicle_path);
  for (const XMLElement* s = vroot->FirstChildElement(); s; s = s->NextSiblingElement()) {
    const std::string tag = s->Name();
    if (tag == "compiler" || tag == "option" || tag == "size") {
      XMLElement* target = ChildOrNew(scene, root, tag.c_str());
      CopyAttributes(s, target);
      for (const XMLElement* c = s->FirstChildElement(); c; c = c->NextSiblingElement()) {
        CopyAttributes(c, ChildOrNew(scene, target, c->Name()));
      }
    } else if (tag == "default" || tag == "asset") {
      MergeNamedChildren(scene, root, s, vdir);
    }
  }
}

// Time step, integrator, contacts and the offscreen buffer the renderers need.
void SetSimulationOptions(XMLDocument& scene, XMLElement* root, const SceneRequest& request) {
  // mj_step1/mj_step2 (the split the controllers need to read sensors of the current state)
  // supports Euler and the implicit integrators, not RK4; the experiments integrate with Euler.
  XMLElement* option = ChildOrNew(scene, root, "option");
  char ts[64];
  std::snprintf(ts, sizeof(ts), "%.17g", request.timestep);
  option->SetAttribute("timestep", ts);
  option->SetAttribute("integrator", "Euler");
  if (request.disable_contacts) {
    ChildOrNew(scene, option, "flag")->SetAttribute("contact", "disable");
  }
  XMLElement* visual = ChildOrNew(scene, root, "visual");
  XMLElement* global = ChildOrNew(scene, visual, "global");
  global->SetAttribute("offwidth",
                       std::max(request.offscreen_width, global->IntAttribute("offwidth")));
  global->SetAttribute("offheight",
                       std::max(request.offscreen_height, global->IntAttribute("offheight")));
}

// 1 + N prefixed copies of the vehicle body and of its per-vehicle sections (actuators, sensors,
// contact pairs/excludes, tendons, equalities).
void AddVehicleCopies(XMLDocument& scene, XMLElement* root, const XMLElement* vroot,
                      const XMLElement* body, const SceneRequest& request) {
  XMLElement* world = ChildOrNew(scene, root, "worldbody");
  const int n_vehicles = static_cast<int>(request.positions.size());
  for (int i = 0; i < n_vehicles; ++i) {
    XMLElement* copy = body->DeepClone(&scene)->ToElement();
    PrefixNames(copy, VehiclePrefix(request.first_vehicle + i));
    copy->SetAttribute("pos", FormatVec(request.positions[i]).c_str());
    world->InsertEndChild(copy);
  }
  for (const char* tag : {"actuator", "sensor", "contact", "tendon", "equality"}) {
    const XMLElement* s = vroot->FirstChildElement(tag);
    if (!s) continue;
    if (request.strip_actuators && std::strcmp(tag, "actuator") == 0) continue;
    XMLElement* target = ChildOrNew(scene, root, tag);
    for (int i = 0; i < n_vehicles; ++i) {
      for (const XMLElement* c = s->FirstChildElement(); c; c = c->NextSiblingElement()) {
        XMLElement* copy = c->DeepClone(&scene)->ToElement();
        PrefixNames(copy, VehiclePrefix(request.first_vehicle + i));
        target->InsertEndChild(copy);
      }
    }
  }
}

}  // namespace

std::string ComposeScene(const SceneRequest& request) {
  XMLDocument scene, vehicle;
  Load(scene, request.scene_path, "scene model");
  if (request.vehicle_xml.empty()) {
    Load(vehicle, request.vehicle_path, "vehicle model");
  } else if (vehicle.Parse(request.vehicle_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw SceneError(request.vehicle_path + " (adapted): " + vehicle.ErrorStr());
  }
  XMLElement* root = scene.RootElement();
  const XMLElement* vroot = vehicle.RootElement();
  root->SetAttribute("model", "mjformation");
  const XMLElement* body = VehicleBody(vroot, request.vehicle_path);
  MergeGlobalSections(scene, root, vroot, request.vehicle_path);
  SetSimulationOptions(scene, root, request);
  AddVehicleCopies(scene, root, vroot, body, request);
  tinyxml2::XMLPrinter printer;
  scene.Print(&printer);
  return std::string("<!-- Composed by mjformation from ") + request.scene_path + " and " +
         std::to_string(request.positions.size()) + " copies of " + request.vehicle_path +
         AdapterNotes(request) + " -->\n" + printer.CStr();
}

mjModel_* CompileModel(const std::string& xml, const std::string& name) {
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* file = "mjformation_scene.xml";
  if (mj_addBufferVFS(&vfs, file, xml.data(), static_cast<int>(xml.size())) != 0) {
    mj_deleteVFS(&vfs);
    throw SceneError(name + ": cannot allocate the in-memory model file");
  }
  char error[1024] = {0};
  mjModel* m = mj_loadXML(file, &vfs, error, sizeof(error));
  mj_deleteVFS(&vfs);
  if (!m) throw SceneError(name + ": MuJoCo cannot load the model: " + error);
  return m;
}

}  // namespace mjf::runner
