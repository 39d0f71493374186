// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjcf_util.hpp"

#include <sys/stat.h>

#include <cstdlib>
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

std::string Describe(const tinyxml2::XMLElement* e) {
  std::string out = std::string("<") + e->Name();
  if (const char* n = e->Attribute("name")) out += std::string(" name=\"") + n + "\"";
  return out + ">";
}

}  // namespace mjf::runner::mjcf
