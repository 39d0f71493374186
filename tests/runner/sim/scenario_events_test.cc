// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The two scenario events in flight: a switching topology ([[topology.switch]]: the formation
// law sees the new graph from the switch on, with its own state carried over) and a rotor fault
// ([[vehicles.fault]]: the rotor's control scaled from the fault's time, in both rotor models).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <string>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/config/config_error.hpp"
#include "mjformation/sim/actuation.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

// The paper's Exp 2 on the point mass for 1 s, with `switches` appended.
ExperimentConfig Exp2PointMass(const std::string& switches) {
  std::string text = mjf::testing::ReadFile(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml");
  text += switches;
  return mjf::testing::Parse(text, "exp2_switch.toml");
}

ExperimentConfig Short(ExperimentConfig c) {
  c.duration = 1.0;
  return c;
}

// Follower positions after each step of a 1 s flight.
std::vector<std::vector<double>> Fly(const ExperimentConfig& config, int steps) {
  ExperimentConfig c = config;
  c.model = "pointmass";
  Simulation sim(c);
  std::vector<std::vector<double>> track;
  for (int s = 0; s < steps; ++s) {
    sim.ComputeControls();
    sim.Integrate();
    std::vector<double> p;
    for (const mjfVehicleState& v : sim.states()) p.insert(p.end(), v.pos, v.pos + 3);
    track.push_back(p);
  }
  return track;
}

const char kRing[] =
    "edges = [[1, 2], [2, 1], [2, 3], [3, 2], [3, 4], [4, 3], [4, 5], [5, 4], [5, 6], [6, 5], "
    "[6, 1], [1, 6]]\n";

// A switch to the graph already flown changes no bit: the new instance takes over the law's
// state (smc_discrete's sampling clock and held command; 0.5127 s is between two samples of
// T = 0.05 s, so a law started afresh would sample at once and move the track).
TEST(ScenarioEventsTest, SwitchToTheSameGraphChangesNothing) {
  const auto plain = Fly(Short(Exp2PointMass("")), 800);
  const auto same =
      Fly(Short(Exp2PointMass(
              std::string("[[topology.switch]]\nat = 0.5127\nleader_links = [1]\n") + kRing)),
          800);
  EXPECT_EQ(plain, same);
}

// A switch to another graph (the leader now talks to follower 4, the followers form a chain
// 4 -> 5 -> 6 -> 1 -> 2 -> 3) leaves the flight bit for bit as it was until the first tick at the
// switch time and changes it after.
TEST(ScenarioEventsTest, SwitchToAnotherGraphActsFromItsTime) {
  const auto plain = Fly(Short(Exp2PointMass("")), 800);
  const auto switched =
      Fly(Short(Exp2PointMass("[[topology.switch]]\nat = 0.5\nleader_links = [4]\n"
                              "edges = [[4, 5], [5, 6], [6, 1], [1, 2], [2, 3]]\n")),
          800);
  // The tick of step 500 commands the step 500 -> 501: positions differ from index 500 on.
  for (int s = 0; s < 500; ++s) ASSERT_EQ(plain[s], switched[s]) << "step " << s;
  EXPECT_NE(plain[799], switched[799]);
}

TEST(ScenarioEventsTest, SwitchNeedsACentralFormationLaw) {
  ExperimentConfig c =
      Short(Exp2PointMass(std::string("[[topology.switch]]\nat = 0.5\nleader_links = [1]\n") +
                          kRing + "[execution]\nmode = \"per_agent\"\n[network]\n"));
  c.model = "pointmass";
  try {
    Simulation sim(c);
    ADD_FAILURE() << "a switch with per-agent execution was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("[topology] switch: a switching topology needs a formation "
                                    "law run centrally"));
  }
}

// A hovering quadrotor follower whose rotor 0 loses half its thrust at 0.1 s: the flight is
// bit for bit the healthy one until then and departs after, in both rotor models.
TEST(ScenarioEventsTest, RotorFaultActsFromItsTimeInBothRotorModels) {
  const std::string healthy = mjf::testing::HoverExperiment(1, 0.3);
  const std::string faulty =
      healthy + "[[vehicles.fault]]\nfollower = 1\nrotor = 0\nat = 0.1\nthrust_share = 0.5\n";
  for (RotorModel model : {RotorModel::kActuator, RotorModel::kWrench}) {
    ExperimentConfig h = mjf::testing::Parse(healthy), f = mjf::testing::Parse(faulty);
    h.rotor_model = f.rotor_model = model;
    Simulation a(h), b(f);
    for (int64_t step = 0; step < 300; ++step) {
      a.ComputeControls();
      b.ComputeControls();
      a.Integrate();
      b.Integrate();
      if (step < 100) {
        ASSERT_EQ(std::memcmp(a.states()[1].pos, b.states()[1].pos, sizeof(double) * 3), 0)
            << "step " << step;
      }
    }
    // The leader is untouched; the follower has rolled off its hover.
    EXPECT_EQ(std::memcmp(a.states()[0].pos, b.states()[0].pos, sizeof(double) * 3), 0);
    EXPECT_NE(std::memcmp(a.states()[1].quat, b.states()[1].quat, sizeof(double) * 4), 0);
  }
}

TEST(ScenarioEventsTest, FaultOnARotorTheVehicleLacksIsRefusedAtItsLine) {
  ExperimentConfig c = mjf::testing::Parse(
      mjf::testing::HoverExperiment(1, 0.3) +
          "[[vehicles.fault]]\nfollower = 1\nrotor = 4\nat = 0.1\nthrust_share = 0.5\n",
      "rotor.toml");
  try {
    Simulation sim(c);
    ADD_FAILURE() << "rotor 4 of a quadrotor was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("rotor.toml:17: [vehicles] fault: rotor 4: the vehicle has "
                                    "rotors 0..3"));
  }
}

}  // namespace
}  // namespace mjf::runner
