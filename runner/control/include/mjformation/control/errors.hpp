// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What can go wrong once a run is under way. Input errors (ConfigError, SceneError,
// PluginError) are thrown before anything is written; these are thrown while stepping.
#ifndef MJFORMATION_CONTROL_ERRORS_HPP_
#define MJFORMATION_CONTROL_ERRORS_HPP_

#include <stdexcept>

namespace mjf::runner {

// The simulation went wrong mid-run (non-finite state, MuJoCo warning or error, plugin failure).
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_ERRORS_HPP_
