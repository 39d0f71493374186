// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "compose/scene_text.hpp"

#include <tinyxml2.h>

#include <cstring>

namespace mjf::runner {
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

// MuJoCo's writer: tinyxml2's printer with two spaces per level, then a blank line before each
// top-level section but the first (xml_native_writer.cc, WriteDoc).
class MujocoPrinter : public tinyxml2::XMLPrinter {
 public:
  MujocoPrinter() : tinyxml2::XMLPrinter(nullptr, /*compact=*/false) {}
  void PrintSpace(int depth) override {
    for (int i = 0; i < depth; ++i) Write("  ");
  }
};

std::string PrintAsMujoco(const XMLDocument& doc) {
  MujocoPrinter printer;
  doc.Print(&printer);
  std::string text = printer.CStr();
  static const char* const kSections[] = {
      "<actuator",   "<asset",     "<compiler",  "<contact>", "<custom",   "<default>",
      "<deformable", "<equality",  "<extension", "<keyframe", "<option",   "<sensor",
      "<size",       "<statistic", "<tendon",    "<visual",   "<worldbody"};
  size_t first_line = std::string::npos;
  for (const char* section : kSections) {
    const size_t length = std::strlen(section);
    for (size_t at = 0; (at = text.find(section, at)) != std::string::npos; at += length) {
      const size_t line = text.rfind('\n', at);
      if (line < first_line) first_line = line;
      if (line != std::string::npos) {
        text.insert(line + 1, 1, '\n');
        ++at;
      }
    }
  }
  if (first_line != std::string::npos) text.erase(first_line, 1);
  return text;
}

// Replaces `e` by its children, in place.
void Splice(XMLElement* e) {
  XMLElement* parent = e->Parent()->ToElement();
  tinyxml2::XMLNode* after = e;
  while (XMLElement* c = e->FirstChildElement()) after = parent->InsertAfterChild(after, c);
  parent->DeleteChild(e);
}

// Whether `e` only groups other elements of its kind: a frame without attributes holding only
// frames, or a block's default class (`marker` in its name) holding only classes.
bool IsWrapper(const XMLElement* e, const char* tag, const char* marker) {
  if (std::strcmp(e->Name(), tag) != 0) return false;
  if (marker) {
    const char* name = e->Attribute("class");
    if (!name || !std::strstr(name, marker)) return false;
  } else if (e->FirstAttribute()) {
    return false;
  }
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::strcmp(c->Name(), tag) != 0) return false;
  }
  return true;
}

// Splices every wrapper among the children of `parent` (and theirs), depth first; false when a
// block's class holds settings of its own (it cannot go without changing its children's).
bool Unwrap(XMLElement* parent, const char* tag, const char* marker) {
  for (XMLElement* e = parent->FirstChildElement(tag); e;) {
    XMLElement* next = e->NextSiblingElement(tag);
    if (!Unwrap(e, tag, marker)) return false;
    if (IsWrapper(e, tag, marker)) {
      Splice(e);
    } else if (marker && e->Attribute("class") && std::strstr(e->Attribute("class"), marker)) {
      return false;
    }
    e = next;
  }
  return true;
}

}  // namespace

std::optional<std::string> WithoutBlocks(const std::string& written, const char* marker) {
  XMLDocument doc(true, tinyxml2::COLLAPSE_WHITESPACE);
  if (doc.Parse(written.c_str()) != tinyxml2::XML_SUCCESS) return std::nullopt;
  XMLElement* root = doc.FirstChildElement("mujoco");
  if (!root) return std::nullopt;
  XMLElement* world = root->FirstChildElement("worldbody");
  XMLElement* defaults = root->FirstChildElement("default");
  if (world && !Unwrap(world, "frame", nullptr)) return std::nullopt;
  if (defaults && !Unwrap(defaults, "default", marker)) return std::nullopt;
  return PrintAsMujoco(doc);
}

}  // namespace mjf::runner
