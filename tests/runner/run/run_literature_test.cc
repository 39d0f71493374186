// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Each formation law from the literature (plugins/formation/README.md) flies the paper's Exp 2
// (experiments/exp2.toml: circling leader, six followers from near the origin, sigma_f(0) =
// 53.8) for its first seconds, with its default (untuned) gains, on the point mass and on the
// quadrotor: the run completes without a safety event (flip, ground impact, collision, near
// miss) and the formation error stays finite.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

struct Flight {
  const char* law;
  bool point_mass;
};

class LiteratureLawFlight : public ::testing::TestWithParam<Flight> {};

TEST_P(LiteratureLawFlight, FliesExp2WithoutASafetyEvent) {
  const Flight flight = GetParam();
  std::vector<std::string> sets = {"run.duration=6.0", "run.metric_window=[0.0, 6.0]",
                                   "render.snapshots=[0.0]",
                                   std::string("formation={plugin=\"") + flight.law + "\"}"};
  if (flight.point_mass) {
    sets.push_back("vehicles.model=\"pointmass\"");
    sets.push_back("attitude={plugin=\"pointmass_direct\"}");
  }
  RunOptions options;
  options.render = false;
  options.out_dir = mjf::testing::TempDir(std::string("lit_") + flight.law) + "/run";
  const RunResult r = RunExperiment(
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", sets), options);
  ASSERT_TRUE(r.complete) << r.error;
  EXPECT_FALSE(r.summary.contains("events")) << r.summary["events"].dump();
  const auto& metrics = r.summary["metrics"];
  ASSERT_TRUE(metrics.contains("sigma_f_final")) << metrics.dump();
  const double final_sigma = metrics["sigma_f_final"].get<double>();
  RecordProperty("sigma_f_at_6s", std::to_string(final_sigma));
  EXPECT_TRUE(std::isfinite(final_sigma));
}

std::string FlightName(const ::testing::TestParamInfo<Flight>& info) {
  return std::string(info.param.law) + (info.param.point_mass ? "_pointmass" : "_quadrotor");
}

INSTANTIATE_TEST_SUITE_P(
    Exp2, LiteratureLawFlight,
    ::testing::Values(Flight{"vs_tracking", true}, Flight{"vs_tracking", false},
                      Flight{"super_twisting", true}, Flight{"super_twisting", false},
                      Flight{"adaptive_tracking", true}, Flight{"adaptive_tracking", false},
                      Flight{"observer_tracking", true}, Flight{"observer_tracking", false},
                      Flight{"terminal_smc", true}, Flight{"terminal_smc", false}),
    FlightName);

}  // namespace
}  // namespace mjf::runner
