// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "scene_replication.hpp"

#include <tinyxml2.h>

#include <cstring>
#include <set>
#include <unordered_set>

namespace mjf::runner {
namespace {

using tinyxml2::XMLAttribute;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

// The sections whose vehicle elements are copied per vehicle, and the others a scene may hold
// (written once, as MuJoCo wrote them with one vehicle; the assets are shared by all copies).
const std::set<std::string> kRepeated = {"default",  "worldbody", "contact", "equality",
                                         "tendon",   "actuator",  "sensor"};
const std::set<std::string> kOnce = {"compiler", "option", "size", "visual", "statistic", "asset"};

// The vehicle's elements in one section: consecutive children of `parent`.
struct Run {
  XMLElement* parent;
  std::vector<XMLElement*> elements;
};

// Same tag and attributes (children not compared).
bool SameTag(const XMLElement* a, const XMLElement* b) {
  if (std::strcmp(a->Name(), b->Name()) != 0) return false;
  const XMLAttribute* x = a->FirstAttribute();
  const XMLAttribute* y = b->FirstAttribute();
  for (; x && y; x = x->Next(), y = y->Next()) {
    if (std::strcmp(x->Name(), y->Name()) != 0 || std::strcmp(x->Value(), y->Value()) != 0) {
      return false;
    }
  }
  return !x && !y;
}

// The children of `with` that `without` (the same section without the vehicle, or null) does
// not have, as runs; false when `without` has a child `with` lacks (not a plain addition).
bool FindRuns(const XMLElement* without, XMLElement* with, std::vector<Run>* runs) {
  const XMLElement* old = without ? without->FirstChildElement() : nullptr;
  Run run{with, {}};
  for (XMLElement* e = with->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (old && SameTag(old, e)) {
      old = old->NextSiblingElement();
      if (!run.elements.empty()) runs->push_back(run);
      run.elements.clear();
    } else {
      run.elements.push_back(e);
    }
  }
  if (!run.elements.empty()) runs->push_back(run);
  return old == nullptr;
}

// Names the copies carry (and rename): element names and default class names.
void CollectNames(const XMLElement* e, std::unordered_set<std::string>* names) {
  if (const char* n = e->Attribute("name")) names->insert(n);
  if (std::strcmp(e->Name(), "default") == 0 && e->Attribute("class")) {
    names->insert(e->Attribute("class"));
  }
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    CollectNames(c, names);
  }
}

// Every attribute of the subtree that names one of `names` (alone, or as one of a
// space-separated list) now names it under `to` instead of `from`.
void Rename(XMLElement* e, const std::unordered_set<std::string>& names, const std::string& from,
            const std::string& to) {
  auto swap = [&](const std::string& v) { return to + v.substr(from.size()); };
  for (const XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
    const std::string value = a->Value();
    if (names.count(value)) {
      e->SetAttribute(a->Name(), swap(value).c_str());
    } else if (value.find(' ') != std::string::npos) {
      std::string out;
      bool changed = false;
      for (size_t start = 0; start <= value.size();) {
        size_t end = value.find(' ', start);
        if (end == std::string::npos) end = value.size();
        const std::string token = value.substr(start, end - start);
        changed |= names.count(token) > 0;
        out += (start ? " " : "") + (names.count(token) ? swap(token) : token);
        start = end + 1;
      }
      if (changed) e->SetAttribute(a->Name(), out.c_str());
    }
  }
  for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    Rename(c, names, from, to);
  }
}

// The vehicle's runs in the text with one vehicle; false when the sections are not all known.
bool VehicleRuns(XMLElement* without, XMLElement* with, std::vector<Run>* runs) {
  for (const XMLElement* s = without->FirstChildElement(); s; s = s->NextSiblingElement()) {
    if (!with->FirstChildElement(s->Name())) return false;
  }
  for (XMLElement* s = with->FirstChildElement(); s; s = s->NextSiblingElement()) {
    if (kOnce.count(s->Name())) continue;
    if (!kRepeated.count(s->Name())) return false;
    const XMLElement* old = without->FirstChildElement(s->Name());
    if (old && old->NextSiblingElement(s->Name())) return false;
    if (!FindRuns(old, s, runs)) return false;
  }
  return true;
}

}  // namespace

std::optional<std::string> ReplicateVehicle(const std::string& without, const std::string& with_one,
                                            const std::vector<std::string>& prefixes) {
  XMLDocument a, b;
  if (a.Parse(without.c_str()) != tinyxml2::XML_SUCCESS ||
      b.Parse(with_one.c_str()) != tinyxml2::XML_SUCCESS) {
    return std::nullopt;
  }
  XMLElement* root_a = a.FirstChildElement("mujoco");
  XMLElement* root_b = b.FirstChildElement("mujoco");
  std::vector<Run> runs;
  if (!root_a || !root_b || !VehicleRuns(root_a, root_b, &runs)) return std::nullopt;
  std::unordered_set<std::string> names;
  for (const Run& run : runs) {
    for (const XMLElement* e : run.elements) CollectNames(e, &names);
  }
  for (const std::string& n : names) {
    if (n.compare(0, prefixes[0].size(), prefixes[0]) != 0) return std::nullopt;
  }
  for (const Run& run : runs) {
    XMLElement* after = run.elements.back();
    for (size_t i = 1; i < prefixes.size(); ++i) {
      for (const XMLElement* e : run.elements) {
        XMLElement* copy = e->DeepClone(&b)->ToElement();
        Rename(copy, names, prefixes[0], prefixes[i]);
        after = run.parent->InsertAfterChild(after, copy)->ToElement();
      }
    }
  }
  tinyxml2::XMLPrinter printer(nullptr, /*compact=*/true);
  b.Print(&printer);
  return std::string(printer.CStr());
}

}  // namespace mjf::runner
