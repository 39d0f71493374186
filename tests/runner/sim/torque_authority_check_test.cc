// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The torque-authority check at set-up (Simulation, what `check` and `run` print): each axis'
// angular acceleration read from a synthetic MJCF of known inertia and control ranges, the
// warning for a vehicle too weak for its attitude loop, none for the stock quadrotor; the
// warning reaches summary.json.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

// A 30 g thrust-and-moment vehicle: roll +-range N m on 2e-5 kg m^2, pitch twice that range on
// 4e-5 (the same rad/s^2), yaw 4e-5 N m on 4e-5 kg m^2 (1 rad/s^2).
std::string Tiny(double range) {
  const std::string r = std::to_string(range), r2 = std::to_string(2 * range);
  return R"(<mujoco model="tiny">
  <compiler autolimits="true"/>
  <worldbody>
    <body name="tiny" pos="0 0 1">
      <freejoint/>
      <inertial pos="0 0 0" mass="0.03" diaginertia="2e-5 4e-5 4e-5"/>
      <geom type="box" size="0.03 0.03 0.01" contype="0" conaffinity="0"/>
      <site name="centre" pos="0 0 0"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="lift" site="centre" gear="0 0 1 0 0 0" ctrlrange="0 0.5"/>
    <motor name="mx" site="centre" gear="0 0 0 -1 0 0" ctrlrange="-)" +
         r + " " + r + R"("/>
    <motor name="my" site="centre" gear="0 0 0 0 -1 0" ctrlrange="-)" +
         r2 + " " + r2 + R"("/>
    <motor name="mz" site="centre" gear="0 0 0 0 0 -1" ctrlrange="-4e-5 4e-5"/>
  </actuator>
</mujoco>
)";
}

ExperimentConfig TinyHover(double range, const std::string& attitude) {
  const std::string model =
      mjf::testing::WriteFile(mjf::testing::TempDir("authority") + "/tiny.xml", Tiny(range));
  return LoadExperiment(
      std::string(MJF_SOURCE_DIR) + "/experiments/hover.toml",
      {"vehicles.model=\"" + model + "\"", "vehicles.body=\"tiny\"", "vehicles.thrust=\"lift\"",
       "vehicles.moments=[\"mx\",\"my\",\"mz\"]", "attitude={plugin=\"" + attitude + "\"}",
       "vehicles.followers=2", "run.duration=0.05", "run.metric_window=[0.0,0.05]",
       "render.snapshots=[]"});
}

TEST(TorqueAuthorityCheckTest, AuthorityOfASyntheticModelIsRangeTimesGearOverInertia) {
  const Simulation sim(TinyHover(1e-5, "geometric"));
  const TorqueAuthority& a = sim.torque_authority();
  ASSERT_TRUE(a.known) << a.why;
  EXPECT_NEAR(a.accel[0], 1e-5 / 2e-5, 1e-9);  // 0.5 rad/s^2
  EXPECT_NEAR(a.accel[1], 2e-5 / 4e-5, 1e-9);
  EXPECT_NEAR(a.accel[2], 4e-5 / 4e-5, 1e-9);
  EXPECT_NEAR(a.inertia[1], 4e-5, 1e-12);
}

TEST(TorqueAuthorityCheckTest, WeakVehicleIsWarnedWithBothPlugins) {
  for (const std::string attitude : {"geometric", "pd_cascade"}) {
    const Simulation sim(TinyHover(1e-5, attitude));
    ASSERT_EQ(sim.warnings().size(), 2u) << attitude;  // roll and pitch differ in torque
    EXPECT_THAT(sim.warnings()[0], HasSubstr("tiny.xml (body 'tiny'): roll torque authority 0.5 "
                                             "rad/s^2"));
    EXPECT_THAT(sim.warnings()[0], HasSubstr("the attitude plugin lowered its default att_bw"));
    EXPECT_THAT(sim.warnings()[1], HasSubstr("pitch torque authority 0.5 rad/s^2"));
    // The plugin's defaults stay within the authority (att_bw^2 tilt_max <= alpha) ...
    const AttitudeDemand& d = sim.attitude_demand();
    EXPECT_LE(d.att_bw * d.att_bw * d.tilt_max, 0.5 * (1 + 1e-9)) << attitude;
    // ... while the loop it was tuned as asks for more.
    EXPECT_GT(DemandedTiltAcceleration(d.Reference(), d.tilt_max), 0.5) << attitude;
  }
  // A thousand times the range (500 rad/s^2) is enough for both (geometric asks 12.5^2 x 0.78).
  for (const std::string attitude : {"geometric", "pd_cascade"}) {
    EXPECT_TRUE(Simulation(TinyHover(1e-2, attitude)).warnings().empty()) << attitude;
  }
}

TEST(TorqueAuthorityCheckTest, StockQuadrotorIsNotWarned) {
  for (const std::string file : {"exp1_exponential.toml", "exp2.toml", "exp3.toml", "hover.toml"}) {
    for (const std::string attitude : {"", "geometric"}) {
      std::vector<std::string> overrides = {"run.duration=1.0", "run.metric_window=[0.0,1.0]",
                                            "render.snapshots=[]"};
      if (!attitude.empty()) overrides.push_back("attitude={plugin=\"" + attitude + "\"}");
      const Simulation sim(
          LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/" + file, overrides));
      ASSERT_TRUE(sim.torque_authority().known) << file;
      EXPECT_NEAR(sim.torque_authority().accel[1], 60.5, 0.1) << file;  // pitch, the weaker
      EXPECT_TRUE(sim.warnings().empty())
          << file << " " << attitude << ": " << sim.warnings().front();
      EXPECT_GT(sim.attitude_demand().att_bw, 0) << file;  // the loop was judged, not skipped
    }
  }
}

TEST(TorqueAuthorityCheckTest, WarningIsRecordedInTheSummary) {
  RunOptions options;  // no run directory: the summary in memory only
  options.render = false;
  options.record = false;
  const RunResult r = RunExperiment(TinyHover(1e-5, "geometric"), options);
  ASSERT_TRUE(r.summary.contains("warnings"));
  EXPECT_EQ(r.summary["warnings"].size(), 2u);
  EXPECT_THAT(r.summary["warnings"][0].get<std::string>(), HasSubstr("roll torque authority"));
  const RunResult strong = RunExperiment(TinyHover(1e-2, "geometric"), options);
  EXPECT_FALSE(strong.summary.contains("warnings"));
}

}  // namespace
}  // namespace mjf::runner
