// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/literature_laws.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {

void RequirePositive(double value, const char* key, const char* source) {
  if (!(value > 0.0 && std::isfinite(value))) {
    std::ostringstream out;
    out << "attribute '" << key << "': " << key << " > 0 is required by " << source << " (got "
        << value << ")";
    throw std::invalid_argument(out.str());
  }
}

}  // namespace mjf::formation
