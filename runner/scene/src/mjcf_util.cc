// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjcf_util.hpp"

#include <sys/stat.h>

#include <cstdlib>
#include <cstring>
#include <memory>

namespace mjf::runner::mjcf {

std::string ModelDirectory(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
  std::unique_ptr<char, decltype(&std::free)> real(realpath(dir.c_str(), nullptr), &std::free);
  return real ? std::string(real.get()) : dir;
}

bool IsFile(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string Join(const std::string& dir, const std::string& rel) {
  if (rel.empty() || rel[0] == '/' || dir.empty()) return rel;
  return dir.back() == '/' ? dir + rel : dir + "/" + rel;
}

std::string At(const std::string& path, const tinyxml2::XMLElement* e) {
  return path + ":" + std::to_string(e->GetLineNum());
}

std::string Describe(const tinyxml2::XMLElement* e) {
  std::string out = std::string("<") + e->Name();
  if (const char* n = e->Attribute("name")) out += std::string(" name=\"") + n + "\"";
  return out + ">";
}

bool HasNamed(const tinyxml2::XMLElement* e, const char* tag, const std::string& name) {
  if (std::strcmp(e->Name(), tag) == 0 && e->Attribute("name", name.c_str())) return true;
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (HasNamed(c, tag, name)) return true;
  }
  return false;
}

void CollectNames(const tinyxml2::XMLElement* e, std::set<std::string>* names) {
  if (const char* n = e->Attribute("name")) names->insert(n);
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    CollectNames(c, names);
  }
}

}  // namespace mjf::runner::mjcf
