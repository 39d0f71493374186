// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The formation plugins inside MuJoCo, on the paper's Exp 2 (experiments/exp2.toml): the ideal
// point mass stays within the discrete protocol's error bound after reaching, and the quadrotor
// achieves the formation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::ReadFile;
using mjf::testing::TempDir;

struct RunData {
  nlohmann::json summary;
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;  // NaN for empty cells
  int Column(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

RunData RunExp2(const std::vector<std::string>& overrides) {
  ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml", overrides);
  RunOptions options;
  options.out_dir = TempDir("exp2") + "/run";
  options.render = false;
  const RunResult r = RunExperiment(c, options);
  EXPECT_TRUE(r.complete) << r.error;
  RunData run;
  run.summary = nlohmann::json::parse(ReadFile(options.out_dir + "/summary.json"));
  std::istringstream csv(ReadFile(options.out_dir + "/timeseries.csv"));
  std::string line, cell;
  std::getline(csv, line);
  std::istringstream header(line);
  while (std::getline(header, cell, ',')) run.header.push_back(cell);
  while (std::getline(csv, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    while (std::getline(cells, cell, ',')) row.push_back(cell.empty() ? NAN : std::stod(cell));
    run.rows.push_back(row);
  }
  return run;
}

// With the point-mass vehicle the discrete protocol's measured sigma_f stays below the
// reported bound once the transient is over (Table 1's window, t >= 25 s). Both bounds the plugin
// reports are checked: (47) as EQUATIONS.md reads it, and the re-derived ultimate bound
// (plugins/formation/README.md).
TEST(FormationInMujocoTest, PointMassDiscreteStaysWithinTheBound) {
  const RunData run =
      RunExp2({"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}"});
  const auto& report = run.summary["plugin_report"];
  const double printed_bound = report["error_bound"].get<double>();
  const double rederived_bound = report["error_bound_rederived"].get<double>();
  ASSERT_FALSE(run.summary["metrics"]["reaching_time_s"].is_null()) << "never reached the band";
  const double reaching = run.summary["metrics"]["reaching_time_s"].get<double>();
  EXPECT_LT(reaching, 20.0);
  // The bounds are ultimate bounds on the error: once s_i is in its band, e_i still decays along
  // the sliding surface (e_p' = -(k1/k2) e_p), so they are checked on Table 1's window.
  const int t = run.Column("t"), sigma = run.Column("sigma_f");
  double worst = 0;
  for (const auto& row : run.rows) {
    if (row[t] >= 25.0) worst = std::max(worst, row[sigma]);
  }
  RecordProperty("max_sigma_f_25_40s", std::to_string(worst));
  RecordProperty("printed_bound_47", std::to_string(printed_bound));
  RecordProperty("rederived_bound", std::to_string(rederived_bound));
  EXPECT_LT(worst, printed_bound);
  EXPECT_LT(worst, rederived_bound);
  // And the band of Theorem 2 holds after reaching, checked on the recorded s_i with Delta
  // computed here from Exp 2's parameters (EQUATIONS.md, Theorem 2), not from the plugin's
  // report or the runner's metric (which accumulates only inside the band it was given):
  // T = 0.05, eps = 0.05, q = 4.5, k2 = 1 (KB = k2 T), u in [-1, 1], a_10 = 1.
  const double T = 0.05, eps = 0.05, q = 4.5, kb = 1.0 * T, span = 2.0;
  const double delta2 = eps * T + 1.0 * kb * span;                         // Delta2
  const double delta1 = (eps * T + 1.0 * kb * span + 1e-6) / (2 - q * T);  // Delta1
  const double delta = std::max(delta1, delta2);
  EXPECT_NEAR(report["delta"].get<double>(), delta, 1e-12);
  // The last recorded time any |s_i| was outside the band: reaching happens before 20 s.
  double last_outside = 0;
  for (const auto& row : run.rows) {
    for (int i = 1; i <= 6; ++i) {
      const std::string p = "uav" + std::to_string(i) + "_";
      if (std::max(std::abs(row[run.Column(p + "sx")]), std::abs(row[run.Column(p + "sy")])) >
          delta) {
        last_outside = row[t];
      }
    }
  }
  RecordProperty("last_time_outside_band_s", std::to_string(last_outside));
  EXPECT_LT(last_outside, 20.0);
}

// With the quadrotor, Exp 2's parameters bring every follower within 1 m of its slot
// by t = 30 s (and it stays there).
TEST(FormationInMujocoTest, QuadrotorExp2ConvergesBy30s) {
  const RunData run = RunExp2({});
  const int t = run.Column("t");
  double worst = 0;
  for (const auto& row : run.rows) {
    if (row[t] < 30.0) continue;
    for (int i = 1; i <= 6; ++i) {
      const std::string p = "uav" + std::to_string(i) + "_";
      worst =
          std::max(worst, std::hypot(row[run.Column(p + "px")] - row[run.Column(p + "slot_x")],
                                     row[run.Column(p + "py")] - row[run.Column(p + "slot_y")]));
    }
  }
  RecordProperty("max_slot_error_after_30s_m", std::to_string(worst));
  EXPECT_LT(worst, 1.0);
  // sigma_f starts near the paper's Fig. 27 value.
  EXPECT_NEAR(run.summary["metrics"]["sigma_f_initial"].get<double>(), 53.8, 0.1);
  // Reached although the quadrotors' |s| (attitude lag) stays above Theorem 2's delta: the band
  // is widened to the smallest delta 2^k that holds |s| over the metric window, and from the
  // reaching time on every recorded |s_i| is inside it (checked here on timeseries.csv).
  const auto& m = run.summary["metrics"];
  ASSERT_FALSE(m["reaching_time_s"].is_null()) << "the formation is reached but not reported";
  const double delta = run.summary["plugin_report"]["delta"].get<double>();
  const double band = m["reaching_band"].get<double>();
  EXPECT_EQ(m["reaching_band_widened_from"].get<double>(), delta);
  EXPECT_GT(band, delta);
  EXPECT_LE(band, 0.1 * m["max_abs_s"].get<double>());
  const double reaching = m["reaching_time_s"].get<double>();
  RecordProperty("reaching_time_s", std::to_string(reaching));
  RecordProperty("reaching_band", std::to_string(band));
  EXPECT_LT(reaching, 30.0);
  double worst_s = 0, last_outside = -1;
  for (const auto& row : run.rows) {
    for (int i = 1; i <= 6; ++i) {
      const std::string p = "uav" + std::to_string(i) + "_";
      const double s =
          std::max(std::abs(row[run.Column(p + "sx")]), std::abs(row[run.Column(p + "sy")]));
      if (row[t] >= reaching) worst_s = std::max(worst_s, s);
      if (s > band) last_outside = row[t];
    }
  }
  EXPECT_LE(worst_s, band);
  EXPECT_NEAR(m["max_abs_s_after_reaching"].get<double>(), worst_s, 1e-6 * band);
  EXPECT_NEAR(reaching, last_outside + 0.01, 1e-9);  // the record period of exp2.toml
}

// Largest follower tilt (deg, angle of body z from vertical) over the whole run, and the largest
// slot error (m) from t_from on.
std::pair<double, double> WorstTiltAndSlotError(const RunData& run, double t_from) {
  const int t = run.Column("t");
  double tilt = 0, slot = 0;
  for (const auto& row : run.rows) {
    for (int i = 1; i <= 6; ++i) {
      const std::string p = "uav" + std::to_string(i) + "_";
      const double c =
          std::cos(row[run.Column(p + "roll")]) * std::cos(row[run.Column(p + "pitch")]);
      tilt = std::max(tilt, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI);
      if (row[t] < t_from) continue;
      slot = std::max(slot, std::hypot(row[run.Column(p + "px")] - row[run.Column(p + "slot_x")],
                                       row[run.Column(p + "py")] - row[run.Column(p + "slot_y")]));
    }
  }
  return {tilt, slot};
}

// At tilt_max 0.78 rad (PX4's 45 deg) pd_cascade flips a follower in Exp 2 (refused
// now); with Euler-rate damping and roll/pitch-first allocation it does not, and the formation is
// reached. geometric at its defaults neither flips nor exceeds the limit by more than 10 deg.
TEST(FormationInMujocoTest, QuadrotorExp2AtTiltMax078DoesNotFlip) {
  const std::vector<std::vector<std::string>> configs = {
      {"attitude.tilt_max=0.78", "attitude.damping=\"euler_rates\"",
       "attitude.allocation=\"roll_pitch_first\""},
      {"attitude={plugin=\"geometric\", tilt_max=0.78}"}};
  for (const auto& overrides : configs) {
    SCOPED_TRACE(overrides.back());
    const auto [tilt, slot] = WorstTiltAndSlotError(RunExp2(overrides), 30.0);
    RecordProperty("max_tilt_deg", std::to_string(tilt));
    EXPECT_LT(tilt, 0.78 * 180 / M_PI + 10);
    EXPECT_LT(slot, 1.0);
  }
}

// accel_limit = "vehicle": the host resolves it from the followers (g tan(tilt_max) for a
// rotorcraft, the actuator range for the point mass) and refuses a vehicle without a bound.
TEST(FormationInMujocoTest, AccelLimitFromTheVehicle) {
  const std::string geometric = "attitude={plugin=\"geometric\", tilt_max=0.35}";
  const RunData quad = RunExp2({geometric, "formation.accel_limit=\"vehicle\"", "run.duration=1.0",
                                "run.metric_window=[0.5, 1.0]", "render.snapshots=[0.0]"});
  const double resolved = std::stod(
      quad.summary["plugins"]["formation"]["attributes"]["accel_limit"].get<std::string>());
  EXPECT_NEAR(resolved, 9.81 * std::tan(0.35), 1e-9);  // the tilt, not the Iris' thrust, binds
  EXPECT_EQ(quad.summary["metrics"]["peak_demanded_accel"].size(), 6u);
  for (const auto& peak : quad.summary["metrics"]["peak_demanded_accel"]) {
    EXPECT_LE(peak.get<double>(), resolved * (1 + 1e-9));
  }
  // An unlimited point mass gives no bound: refused before anything runs, naming the key.
  ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
                     {"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}",
                      "formation.accel_limit=\"vehicle\""});
  RunOptions options;
  options.out_dir = TempDir("exp2_unlimited") + "/run";
  options.render = false;
  try {
    const RunResult r = RunExperiment(c, options);
    EXPECT_FALSE(r.complete);
    EXPECT_NE(r.error.find("[formation] accel_limit"), std::string::npos) << r.error;
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("[formation] accel_limit"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::runner
