// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The experiment sections the native swarm plugin carries, every key of each: `mjformation
// export` writes each as one <config> key of the mjformation.swarm instance, and the plugin
// reads them back (mujoco_plugin/src/swarm_host.hpp). One list for both sides.
#ifndef MJFORMATION_EXPORT_CARRIED_SECTIONS_HPP_
#define MJFORMATION_EXPORT_CARRIED_SECTIONS_HPP_

#include <string>
#include <vector>

namespace mjf::runner {

inline const std::vector<std::string>& CarriedSections() {
  static const std::vector<std::string> kSections = {
      "run",     "vehicles",  "topology",  "leader",  "formation", "attitude",
      "sensors", "estimator", "execution", "network", "wind"};
  return kSections;
}

}  // namespace mjf::runner

#endif  // MJFORMATION_EXPORT_CARRIED_SECTIONS_HPP_
