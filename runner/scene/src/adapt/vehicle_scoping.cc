// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapt/vehicle_scoping.hpp"

#include <cstring>
#include <set>

#include "mjcf_util.hpp"

namespace mjf::runner {
namespace {

using mjcf::Describe;
using tinyxml2::XMLElement;

// Sections a vehicle brings into the composed scene (scene.cc copies these and only these).
const std::set<std::string> kKeptSections = {"compiler", "option",    "size",     "default",
                                             "asset",    "worldbody", "actuator", "sensor",
                                             "contact",  "tendon",    "equality"};

const char* const kDefaultsClass = "mjf_vehicle_defaults";

void DropLights(XMLElement* parent, Notes* notes) {
  for (XMLElement* e = parent->FirstChildElement(); e;) {
    XMLElement* next = e->NextSiblingElement();
    if (std::strcmp(e->Name(), "light") == 0) {
      notes->push_back("dropped " + Describe(e) + " (line " + std::to_string(e->GetLineNum()) +
                       "): lights are the scene's");
      parent->DeleteChild(e);
    } else {
      DropLights(e, notes);
    }
    e = next;
  }
}

// Elements that used the top-level defaults now name the class: the body's subtree through
// childclass (a childclass it has already is nested in the class and inherits from it), the
// sections outside the body and the assets that take defaults.
void UseDefaultsClass(XMLElement* root, XMLElement* body) {
  if (!body->Attribute("childclass")) body->SetAttribute("childclass", kDefaultsClass);
  for (const char* tag : {"actuator", "tendon", "equality", "contact"}) {
    XMLElement* section = root->FirstChildElement(tag);
    for (XMLElement* e = section ? section->FirstChildElement() : nullptr; e;
         e = e->NextSiblingElement()) {
      if (!e->Attribute("class") && std::strcmp(e->Name(), "exclude") != 0) {
        e->SetAttribute("class", kDefaultsClass);
      }
    }
  }
  if (XMLElement* asset = root->FirstChildElement("asset")) {
    for (XMLElement* e = asset->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const bool takes_class =
          std::strcmp(e->Name(), "mesh") == 0 || std::strcmp(e->Name(), "material") == 0;
      if (takes_class && !e->Attribute("class")) e->SetAttribute("class", kDefaultsClass);
    }
  }
}

bool RefersOutside(const XMLElement* e, const std::set<std::string>& names) {
  for (const auto& ref : mjcf::kReferenceAttributes) {
    const char* v = e->Attribute(ref.name);
    if (v && !names.count(v)) return true;
  }
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (RefersOutside(c, names)) return true;
  }
  return false;
}

}  // namespace

void ScopeDefaults(tinyxml2::XMLDocument* doc, XMLElement* root, XMLElement* body, Notes* notes) {
  XMLElement* def = root->FirstChildElement("default");
  if (!def) return;
  bool has_main = false;
  for (XMLElement* c = def->FirstChildElement(); c; c = c->NextSiblingElement()) {
    has_main |= std::strcmp(c->Name(), "default") != 0;
  }
  if (!has_main) return;
  XMLElement* scoped = doc->NewElement("default");
  scoped->SetAttribute("class", kDefaultsClass);
  while (XMLElement* c = def->FirstChildElement()) scoped->InsertEndChild(c);
  def->InsertEndChild(scoped);
  UseDefaultsClass(root, body);
  notes->push_back(std::string("scoped the model's top-level <default> settings to the vehicle ") +
                   "(class " + kDefaultsClass + "), so they do not reach the shared scene");
}

void ScopeSizes(XMLElement* root, Notes* notes) {
  XMLElement* size = root->FirstChildElement("size");
  if (!size) return;
  for (const char* a : {"njmax", "nconmax", "nstack", "memory"}) {
    if (size->Attribute(a)) {
      notes->push_back(std::string("dropped <size ") + a + "=\"" + size->Attribute(a) +
                       "\">: sized for one vehicle, not the swarm");
      size->DeleteAttribute(a);
    }
  }
}

void DropWorldExtras(XMLElement* body, Notes* notes) {
  XMLElement* world = body->Parent()->ToElement();
  for (XMLElement* e = world->FirstChildElement(); e;) {
    XMLElement* next = e->NextSiblingElement();
    if (e != body) {
      notes->push_back("dropped " + Describe(e) + " (line " + std::to_string(e->GetLineNum()) +
                       "): world-level, not part of the vehicle");
      world->DeleteChild(e);
    }
    e = next;
  }
  DropLights(body, notes);
}

void NoteModelOptions(const XMLElement* root, Notes* notes) {
  const XMLElement* option = root->FirstChildElement("option");
  if (!option) return;
  for (const char* a : {"timestep", "integrator"}) {
    if (const char* v = option->Attribute(a)) {
      notes->push_back(std::string("the model's <option ") + a + "=\"" + v +
                       "\"> is replaced by the experiment's ([run] timestep; integrator Euler: "
                       "the runner's mj_step1/mj_step2 split cannot run RK4)");
    }
  }
  for (const char* a : {"gravity", "density", "viscosity", "wind"}) {
    if (const char* v = option->Attribute(a)) {
      notes->push_back(std::string("kept the model's <option ") + a + "=\"" + v +
                       "\"> for the whole scene" +
                       (std::string(a) == "gravity" ? ""
                                                    : ": MuJoCo's fluid forces act on every "
                                                      "vehicle alike"));
    }
  }
  for (const XMLElement* f = option->FirstChildElement("flag"); f;
       f = f->NextSiblingElement("flag")) {
    for (auto* at = f->FirstAttribute(); at; at = at->Next()) {
      notes->push_back(std::string("kept the model's <flag ") + at->Name() + "=\"" + at->Value() +
                       "\"> for the whole scene");
    }
  }
}

void DropSections(XMLElement* root, Notes* notes) {
  for (XMLElement* s = root->FirstChildElement(); s;) {
    XMLElement* next = s->NextSiblingElement();
    if (!kKeptSections.count(s->Name())) {
      notes->push_back(std::string("dropped <") + s->Name() + "> (line " +
                       std::to_string(s->GetLineNum()) + "): a vehicle brings no " + s->Name() +
                       " into the shared scene");
      root->DeleteChild(s);
    }
    s = next;
  }
}

void DropDanglingReferences(XMLElement* root, const XMLElement* body, Notes* notes) {
  std::set<std::string> names;
  mjcf::CollectNames(body, &names);
  for (const char* tag : {"tendon", "actuator"}) {
    if (XMLElement* s = root->FirstChildElement(tag)) mjcf::CollectNames(s, &names);
  }
  for (const char* tag : {"tendon", "actuator", "sensor", "contact", "equality"}) {
    XMLElement* s = root->FirstChildElement(tag);
    for (XMLElement* e = s ? s->FirstChildElement() : nullptr; e;) {
      XMLElement* next = e->NextSiblingElement();
      if (RefersOutside(e, names)) {
        notes->push_back("dropped <" + std::string(tag) + "> " + Describe(e) + " (line " +
                         std::to_string(e->GetLineNum()) +
                         "): refers to an element outside the vehicle");
        s->DeleteChild(e);
      }
      e = next;
    }
  }
}

}  // namespace mjf::runner
