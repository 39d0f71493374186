// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjcf_util.hpp"

#include <cstdlib>
#include <memory>

namespace mjf::runner::mjcf {

std::string ModelDirectory(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
  std::unique_ptr<char, decltype(&std::free)> real(realpath(dir.c_str(), nullptr), &std::free);
  return real ? std::string(real.get()) : dir;
}

}  // namespace mjf::runner::mjcf
