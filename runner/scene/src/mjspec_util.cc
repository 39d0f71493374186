// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjspec_util.hpp"

#include <regex>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner::spec {

SpecPtr Parse(const std::string& path, const std::string& xml, const std::string& what_file,
              const char* what) {
  char error[1024] = {0};
  SpecPtr s(xml.empty() ? mj_parseXML(path.c_str(), nullptr, error, sizeof(error))
                        : mj_parseXMLString(xml.c_str(), nullptr, error, sizeof(error)));
  if (s) return s;
  // MuJoCo names the line as "Line number=N" (XML syntax) or "line N" (an element).
  std::string message = error;
  std::smatch line;
  std::string where = what_file;
  if (std::regex_search(message, line, std::regex("[Ll]ine(?: number=| )([0-9]+)"))) {
    where += ":" + line[1].str();
  }
  for (char& c : message) c = c == '\n' ? ' ' : c;
  while (!message.empty() && message.back() == ' ') message.pop_back();
  throw SceneError(where + ": cannot read the " + what + ": " + message);
}

std::vector<mjsElement*> Elements(mjSpec* s, mjtObj type) {
  std::vector<mjsElement*> out;
  for (mjsElement* e = mjs_firstElement(s, type); e; e = mjs_nextElement(s, e)) out.push_back(e);
  return out;
}

void DeleteAll(mjSpec* s, mjtObj type) {
  for (mjsElement* e : Elements(s, type)) mjs_delete(s, e);
}

std::set<std::string> AssetNames(mjSpec* s) {
  std::set<std::string> names;
  for (mjtObj type : kAssetTypes) {
    for (mjsElement* e : Elements(s, type)) names.insert(Name(e));
  }
  return names;
}

std::string SaveXml(mjSpec* s, const std::string& name, size_t size_hint) {
  s->compiler.savecompiled = 0;
  char error[1024] = {0};
  std::string xml(size_hint, '\0');
  int need = mj_saveXMLString(s, xml.data(), static_cast<int>(xml.size()), error, sizeof(error));
  if (need > 0) {  // the buffer was too small: MuJoCo said how large it must be
    xml.assign(need + 1, '\0');
    need = mj_saveXMLString(s, xml.data(), static_cast<int>(xml.size()), error, sizeof(error));
  }
  if (need != 0) throw SceneError(name + ": MuJoCo cannot write the model: " + error);
  xml.resize(xml.find('\0'));
  return xml;
}

}  // namespace mjf::runner::spec
