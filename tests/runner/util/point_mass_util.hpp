// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A tiny experiment for the runner's unit tests: a point-mass leader and two followers at
// chosen places, hover guidance, fixed offsets as the formation. Builds in milliseconds.
#ifndef MJFORMATION_TESTS_RUNNER_POINT_MASS_UTIL_HPP_
#define MJFORMATION_TESTS_RUNNER_POINT_MASS_UTIL_HPP_

#include <sstream>
#include <string>

namespace mjf::testing {

// Leader at (0, 0), followers at (f1x, f1y) and (f2x, f2y), slots at offsets (-2, 0) and (2, 0)
// from the leader, altitude 2 m. `run_extra` / `extra` are appended to [run] / the end.
inline std::string PointMassExperiment(double f1x, double f1y, double f2x, double f2y,
                                       double duration = 0.02, const std::string& run_extra = "",
                                       const std::string& extra = "",
                                       const std::string& shape = "offsets") {
  std::ostringstream t;
  t.precision(17);
  t << "[run]\nname = \"unit\"\nduration = " << duration << "\n"
    << "metric_window = [0.0, " << duration << "]\n"
    << run_extra << "[vehicles]\nmodel = \"pointmass\"\nfollowers = 2\naltitude = 2.0\n"
    << "leader_start = [0.0, 0.0]\nfollower_start = [[" << f1x << ", " << f1y << "], [" << f2x
    << ", " << f2y << "]]\n"
    << "[topology]\nleader_links = [1]\nedges = [[1, 2]]\n"
    << "[leader]\nplugin = \"hover\"\n[formation]\nplugin = \"hover\"\n"
    << "[formation.shape]\ntype = \"" << shape << "\"\n"
    << (shape == "offsets" ? "offsets = [[-2.0, 0.0], [2.0, 0.0]]\n" : "")
    << "[attitude]\nplugin = \"pointmass_direct\"\n"
    << extra;
  return t.str();
}

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_RUNNER_POINT_MASS_UTIL_HPP_
