// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [[topology.switch]] and [[vehicles.fault]] as the parser reads them: values in, and every bad
// entry refused at load naming the file, line and key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "error_of.hpp"
#include "mjformation/config/config.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::ErrorOf;
using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using ::testing::AllOf;
using ::testing::HasSubstr;

// Three followers, 10 s; `extra` appended after the hover file's [topology] (its 16 lines end
// with [attitude], so an appended table's header is on line 17).
std::string WithExtra(const std::string& extra) { return HoverExperiment(3, 10.0) + extra; }

TEST(ScenarioEventsConfigTest, SwitchesAreReadInTimeOrder) {
  const ExperimentConfig c = Parse(WithExtra(
      "[[topology.switch]]\nat = 2.5\nleader_links = [2]\nedges = [[2, 1], [2, 3, 0.5]]\n"
      "[[topology.switch]]\nat = 6.0\nleader_links = [1]\nleader_weights = [2.0, 0.0, 0.0]\n"
      "edges = [[1, 2], [2, 3]]\n"));
  ASSERT_EQ(c.topology_switches.size(), 2u);
  const auto& first = c.topology_switches[0];
  EXPECT_DOUBLE_EQ(first.at, 2.5);
  EXPECT_EQ(first.leader_weight, (std::vector<double>{0.0, 1.0, 0.0}));
  ASSERT_EQ(first.edges.size(), 2u);
  EXPECT_EQ(first.edges[1].from, 1);  // 0-based
  EXPECT_EQ(first.edges[1].to, 2);
  EXPECT_DOUBLE_EQ(first.edges[1].weight, 0.5);
  EXPECT_EQ(first.line, 17);
  EXPECT_EQ(c.topology_switches[1].leader_weight, (std::vector<double>{2.0, 0.0, 0.0}));
  EXPECT_TRUE(Parse(HoverExperiment(3, 10.0)).topology_switches.empty());
}

TEST(ScenarioEventsConfigTest, SwitchWithoutSpanningTreeIsRefusedAtItsLine) {
  // Follower 3 hears no one after the switch.
  const std::string text =
      WithExtra("[[topology.switch]]\nat = 2.0\nleader_links = [1]\nedges = [[1, 2]]\n");
  EXPECT_THAT(ErrorOf([&] { Parse(text, "sw.toml"); }),
              AllOf(HasSubstr("sw.toml:20"), HasSubstr("[topology] switch[1] edges"),
                    HasSubstr("Assumption 2"), HasSubstr("follower 3")));
}

TEST(ScenarioEventsConfigTest, BadSwitchesAreRefused) {
  const std::string chain = "leader_links = [1]\nedges = [[1, 2], [2, 3]]\n";
  EXPECT_THAT(ErrorOf([&] { Parse(WithExtra("[[topology.switch]]\n" + chain)); }),
              AllOf(HasSubstr("switch[1] at"), HasSubstr("missing")));
  EXPECT_THAT(ErrorOf([&] { Parse(WithExtra("[[topology.switch]]\nt = 1.0\n" + chain)); }),
              AllOf(HasSubstr("switch[1] t"), HasSubstr("unknown key")));
  EXPECT_THAT(ErrorOf([&] { Parse(WithExtra("[[topology.switch]]\nat = 10.0\n" + chain)); }),
              AllOf(HasSubstr("switch[1] at"), HasSubstr("inside the run")));
  EXPECT_THAT(ErrorOf([&] {
                Parse(WithExtra("[[topology.switch]]\nat = 5.0\n" + chain +
                                "[[topology.switch]]\nat = 4.0\n" + chain));
              }),
              HasSubstr("increasing time"));
  EXPECT_THAT(ErrorOf([&] { Parse(WithExtra("[[topology.switch]]\nat = 1.0\nedges = []\n")); }),
              AllOf(HasSubstr("switch[1] leader_links"), HasSubstr("missing")));
  EXPECT_THAT(
      ErrorOf([&] { Parse(WithExtra("[[topology.switch]]\nat = 1.0\nwhen = 2\n" + chain)); }),
      AllOf(HasSubstr("when"), HasSubstr("unknown key")));
}

TEST(ScenarioEventsConfigTest, FaultsAreRead) {
  const ExperimentConfig c = Parse(
      WithExtra("[[vehicles.fault]]\nfollower = 3\nrotor = 2\nat = 4.5\nthrust_share = 0.25\n"));
  ASSERT_EQ(c.rotor_faults.size(), 1u);
  EXPECT_EQ(c.rotor_faults[0].follower, 3);
  EXPECT_EQ(c.rotor_faults[0].rotor, 2);
  EXPECT_DOUBLE_EQ(c.rotor_faults[0].at, 4.5);
  EXPECT_DOUBLE_EQ(c.rotor_faults[0].thrust_share, 0.25);
  EXPECT_EQ(c.rotor_faults[0].line, 17);
  EXPECT_TRUE(Parse(HoverExperiment(3, 10.0)).rotor_faults.empty());
}

TEST(ScenarioEventsConfigTest, BadFaultsAreRefusedNamingTheKey) {
  auto fault = [](const std::string& follower, const std::string& share) {
    return WithExtra("[[vehicles.fault]]\nfollower = " + follower +
                     "\nrotor = 0\nat = 1.0\nthrust_share = " + share + "\n");
  };
  EXPECT_THAT(ErrorOf([&] { Parse(fault("4", "0.5"), "f.toml"); }),
              AllOf(HasSubstr("f.toml:18"), HasSubstr("fault[1] follower"), HasSubstr("1..3")));
  EXPECT_THAT(ErrorOf([&] { Parse(fault("1", "1.5")); }),
              AllOf(HasSubstr("fault[1] thrust_share"), HasSubstr("[0, 1]")));
  EXPECT_THAT(ErrorOf([&] { Parse(WithExtra("[[vehicles.fault]]\nfollower = 1\nrotor = 0\n")); }),
              AllOf(HasSubstr("fault[1] at"), HasSubstr("missing")));
  // A misspelt key is named as written, not reported as the key it was meant to be.
  EXPECT_THAT(ErrorOf([&] {
                Parse(WithExtra(
                    "[[vehicles.fault]]\nfollower = 1\nrotor = 0\nat = 1.0\nthrust_shar = 0.5\n"));
              }),
              AllOf(HasSubstr("fault[1] thrust_shar"), HasSubstr("unknown key")));
  // The point mass has no rotors: refused by name rather than ignored.
  std::string point_mass = fault("1", "0.5");
  point_mass.replace(point_mass.find("\"quadrotor\""), 11, "\"pointmass\"");
  EXPECT_THAT(ErrorOf([&] { Parse(point_mass); }),
              AllOf(HasSubstr("[vehicles] fault"), HasSubstr("not the point mass")));
}

}  // namespace
}  // namespace mjf::runner
