// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/wind_params.hpp"

namespace mjf::realism {

bool WindParams::IsCalm() const {
  return mean[0] == 0 && mean[1] == 0 && mean[2] == 0 && !turbulence && gusts.empty();
}

}  // namespace mjf::realism
