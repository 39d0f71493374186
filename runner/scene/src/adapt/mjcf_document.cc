// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapt/mjcf_document.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "mjcf_util.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner::mjcf {
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

// <include file="..."/>: replaced by the children of the included file's <mujoco>, the file
// found relative to the model's folder (as MuJoCo does). An included file's own includes are
// resolved in that file before its elements are copied, so every message names the file and line
// it comes from (a copied element has no line). `chain` holds the files being included, outermost
// first: a file that reappears in it is an include cycle.
void InlineIncludes(const std::string& path, const std::string& dir, XMLDocument* doc,
                    XMLElement* parent, std::vector<std::string>* chain, int* count) {
  for (XMLElement* e = parent->FirstChildElement(); e;) {
    if (std::strcmp(e->Name(), "include") != 0) {
      InlineIncludes(path, dir, doc, e, chain, count);
      e = e->NextSiblingElement();
      continue;
    }
    if (++*count > 100) throw SceneError(At(path, e) + ": more than 100 <include>s");
    const char* file = e->Attribute("file");
    if (!file) throw SceneError(At(path, e) + ": <include> without file");
    const std::string included = Join(dir, file);
    std::error_code ec;
    const std::string key = std::filesystem::weakly_canonical(included, ec).string();
    if (std::find(chain->begin(), chain->end(), key) != chain->end()) {
      std::string cycle;
      for (const std::string& f : *chain) cycle += f + " -> ";
      throw SceneError(At(path, e) + ": <include file=\"" + file + "\"> is an include cycle (" +
                       cycle + key + ")");
    }
    XMLDocument inc;
    if (inc.LoadFile(included.c_str()) != tinyxml2::XML_SUCCESS || !inc.RootElement()) {
      throw SceneError(At(path, e) + ": <include file=\"" + file + "\">: cannot read " + included);
    }
    chain->push_back(key);
    InlineIncludes(included, dir, &inc, inc.RootElement(), chain, count);
    chain->pop_back();
    tinyxml2::XMLNode* after = e;
    for (const XMLElement* c = inc.RootElement()->FirstChildElement(); c;
         c = c->NextSiblingElement()) {
      after = parent->InsertAfterChild(after, c->DeepClone(doc));
    }
    XMLElement* next = after->ToElement() ? after->ToElement()->NextSiblingElement() : nullptr;
    if (after == e) next = e->NextSiblingElement();
    parent->DeleteChild(e);
    e = next;  // the copied elements are resolved already
  }
}

// MuJoCo allows a section several times (includes produce that); scene.cc reads the first.
// Sections of elements are concatenated; <compiler>, <option> and <size> are attribute sets,
// where a later value overrides an earlier one.
void MergeRepeatedSections(XMLElement* root) {
  std::map<std::string, XMLElement*> first;
  for (XMLElement* s = root->FirstChildElement(); s;) {
    XMLElement* next = s->NextSiblingElement();
    auto [it, inserted] = first.emplace(s->Name(), s);
    if (!inserted && std::strcmp(s->Name(), "compiler") != 0 &&
        std::strcmp(s->Name(), "option") != 0 && std::strcmp(s->Name(), "size") != 0) {
      while (XMLElement* c = s->FirstChildElement()) it->second->InsertEndChild(c);
      root->DeleteChild(s);
    } else if (!inserted) {
      for (auto* a = s->FirstAttribute(); a; a = a->Next())
        it->second->SetAttribute(a->Name(), a->Value());
      root->DeleteChild(s);
    }
    s = next;
  }
}

}  // namespace

XMLElement* ReadModelDocument(const std::string& path, const std::string& dir,
                              const std::string& where, XMLDocument* doc) {
  if (doc->LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw SceneError(where + ": cannot read the vehicle model " + path + ":" +
                     std::to_string(doc->ErrorLineNum()) + ": " + doc->ErrorStr());
  }
  XMLElement* root = doc->RootElement();
  if (!root || std::strcmp(root->Name(), "mujoco") != 0) {
    throw SceneError(path + ": not MJCF (no <mujoco> root)");
  }
  int includes = 0;
  std::error_code ec;
  std::vector<std::string> chain = {std::filesystem::weakly_canonical(path, ec).string()};
  InlineIncludes(path, dir, doc, root, &chain, &includes);
  MergeRepeatedSections(root);
  return root;
}

}  // namespace mjf::runner::mjcf
