// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [execution] and [network]: defaults, overrides, and every bad value refused with
// FILE:LINE: [section] key and the reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.hpp"
#include "mjformation/config/experiment.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// Leader -> 1 -> 2 -> 3, per-agent execution, then `extra` (more sections).
std::string Experiment(const std::string& execution, const std::string& extra) {
  return "[run]\nname = \"net\"\nduration = 2.0\ntimestep = 0.001\n"
         "[vehicles]\nmodel = \"pointmass\"\nfollowers = 3\n"
         "[topology]\nleader_links = [1]\nedges = [[1, 2], [2, 3]]\n"
         "[leader]\nplugin = \"hover\"\n[formation]\nplugin = \"hover\"\n"
         "[attitude]\nplugin = \"pointmass_direct\"\n" +
         execution + extra;
}

const char kPerAgent[] = "[execution]\nmode = \"per_agent\"\n";

std::string ErrorOf(const std::string& text) {
  return mjf::testing::ErrorOf([&] { mjf::testing::Parse(text, "net.toml"); });
}

TEST(NetworkConfigTest, DefaultsAreCentralAndIdeal) {
  const ExperimentConfig c = mjf::testing::Parse(Experiment("", ""));
  EXPECT_EQ(c.network.execution, Execution::kCentral);
  EXPECT_EQ(c.network.defaults.period_steps, 1);
  EXPECT_EQ(c.network.defaults.latency, 0.0);
  EXPECT_EQ(c.network.defaults.loss, 0.0);
  EXPECT_TRUE(c.network.links.empty());
}

TEST(NetworkConfigTest, DefaultsAndOverridesParse) {
  const ExperimentConfig c = mjf::testing::Parse(Experiment(
      "[execution]\nmode = \"per_agent\"\ncoupling = \"jacobi\"\njacobi_rounds = 3\n",
      "[network]\nrate = 50.0\nlatency = 0.02\njitter = 0.005\nloss = 0.1\n"
      "[[network.link]]\nfrom = 0\nto = 1\nlatency = 0.0\nloss_model = \"gilbert_elliott\"\n"
      "burst_enter = 0.01\nburst_exit = 0.2\n"
      "[[network.link]]\nfrom = 2\nto = 3\nrange = 15.0\n"));
  EXPECT_EQ(c.network.execution, Execution::kPerAgent);
  EXPECT_EQ(c.network.coupling, Coupling::kJacobi);
  EXPECT_EQ(c.network.jacobi_rounds, 3);
  EXPECT_EQ(c.network.defaults.period_steps, 20);
  EXPECT_EQ(c.network.defaults.latency, 0.02);
  ASSERT_EQ(c.network.links.size(), 2u);
  EXPECT_EQ(c.network.links[0].params.latency, 0.0);
  EXPECT_EQ(c.network.links[0].params.loss, 0.1);  // inherited from [network]
  EXPECT_EQ(c.network.links[0].params.loss_model, network::LossModel::kGilbertElliott);
  EXPECT_EQ(c.network.links[1].params.range, 15.0);
  EXPECT_EQ(c.network.links[1].params.period_steps, 20);
}

struct BadCase {
  const char* network;
  const char* where;   // "net.toml:LINE: [section] key"
  const char* reason;  // part of the reason
};

TEST(NetworkConfigTest, BadValuesNameFileLineSectionKey) {
  // Experiment() has 16 lines; [execution] 2 more; [network] is line 19.
  const BadCase cases[] = {
      {"[network]\nlatency = -0.01\n", "net.toml:20: [network] latency", "must be in [0, "},
      {"[network]\njitter = -1\n", "net.toml:20: [network] jitter", "must be in [0, "},
      {"[network]\nloss = 1.5\n", "net.toml:20: [network] loss", "[0, 1]"},
      {"[network]\nloss = -0.1\n", "net.toml:20: [network] loss", "[0, 1]"},
      {"[network]\nburst_enter = 2.0\n", "net.toml:20: [network] burst_enter", "probability"},
      {"[network]\nburst_exit = -0.5\n", "net.toml:20: [network] burst_exit", "probability"},
      {"[network]\nburst_loss = 1.01\n", "net.toml:20: [network] burst_loss", "probability"},
      {"[network]\nrate = 300.0\n", "net.toml:20: [network] rate", "whole number"},
      {"[network]\nrate = 2000.0\n", "net.toml:20: [network] rate", "whole number"},
      {"[network]\nrange = 0.0\n", "net.toml:20: [network] range", "> 0"},
      {"[network]\nrange = -5.0\n", "net.toml:20: [network] range", "> 0"},
      {"[network]\nloss_model = \"burst\"\n", "net.toml:20: [network] loss_model", "bernoulli"},
      {"[network]\nlatncy = 0.1\n", "net.toml:20: [network] latncy", "unknown key"},
      // One wording for type errors in every section (the shared section reader).
      {"[network]\nlatency = \"fast\"\n", "net.toml:20: [network] latency",
       "expected a number, got a string"},
      {"[network]\nloss_model = 1\n", "net.toml:20: [network] loss_model",
       "expected a string, got an integer"},
      {"[[network.link]]\nfrom = 1\nto = 3\n", "net.toml:19: [network.link] from",
       "1 -> 3 is not in the graph"},
      {"[[network.link]]\nfrom = 0\nto = 2\n", "net.toml:19: [network.link] from",
       "0 -> 2 is not in the graph"},
      {"[[network.link]]\nfrom = 2\nto = 1\n", "net.toml:19: [network.link] from",
       "2 -> 1 is not in the graph"},
      {"[[network.link]]\nfrom = 1\nto = 2\nloss = 3\n", "net.toml:22: [network.link] loss",
       "[0, 1]"},
  };
  for (const BadCase& b : cases) {
    EXPECT_THAT(ErrorOf(Experiment(kPerAgent, b.network)),
                AllOf(HasSubstr(b.where), HasSubstr(b.reason)))
        << b.network;
  }
}

TEST(NetworkConfigTest, ExecutionKeysAreChecked) {
  EXPECT_THAT(ErrorOf(Experiment("", "[network]\nlatency = 0.01\n")),
              AllOf(HasSubstr("net.toml:17: [network]"), HasSubstr("per_agent")));
  EXPECT_THAT(ErrorOf(Experiment("[execution]\nmode = \"distributed\"\n", "")),
              AllOf(HasSubstr("net.toml:18: [execution] mode"), HasSubstr("per_agent")));
  EXPECT_THAT(ErrorOf(Experiment("[execution]\nmode = \"per_agent\"\ncoupling = \"gauss\"\n", "")),
              AllOf(HasSubstr("net.toml:19: [execution] coupling"), HasSubstr("jacobi")));
  EXPECT_THAT(ErrorOf(Experiment("[execution]\nmode = \"per_agent\"\njacobi_rounds = 2\n", "")),
              AllOf(HasSubstr("net.toml:19: [execution] jacobi_rounds"), HasSubstr("jacobi")));
  EXPECT_THAT(
      ErrorOf(Experiment(
          "[execution]\nmode = \"per_agent\"\ncoupling = \"jacobi\"\njacobi_rounds = 0\n", "")),
      AllOf(HasSubstr("net.toml:20: [execution] jacobi_rounds"), HasSubstr("[1, 64]")));
}

// [network] rounds: the default is today's instantaneous rounds; an unknown value, a
// timeout without rounds over links, and a latency with which not one round fits a sample (the
// test file's law samples every step: T = the 1 ms timestep) are refused at the key's line.
TEST(NetworkConfigTest, ExchangeRoundsAreChecked) {
  const std::string jacobi = "[execution]\nmode = \"per_agent\"\ncoupling = \"jacobi\"\n";
  const std::string central = "[execution]\nmode = \"per_agent\"\ncoupling = \"central_solve\"\n";
  EXPECT_EQ(mjf::testing::Parse(Experiment(jacobi, ""), "net.toml").network.rounds,
            ExchangeRounds::kInstantaneous);
  const ExperimentConfig over = mjf::testing::Parse(
      Experiment(jacobi, "[network]\nrounds = \"over_links\"\nround_timeout = 0.5\n"), "net.toml");
  EXPECT_EQ(over.network.rounds, ExchangeRounds::kOverLinks);
  EXPECT_EQ(over.network.round_timeout, 0.5);
  // Experiment() has 16 lines; [execution] 3 more; [network] is line 20.
  EXPECT_THAT(ErrorOf(Experiment(jacobi, "[network]\nrounds = \"radio\"\n")),
              AllOf(HasSubstr("net.toml:21: [network] rounds"), HasSubstr("over_links"),
                    HasSubstr("(got \"radio\")")));
  EXPECT_THAT(ErrorOf(Experiment(jacobi, "[network]\nround_timeout = 0.01\n")),
              AllOf(HasSubstr("net.toml:21: [network] round_timeout"), HasSubstr("over_links")));
  EXPECT_THAT(
      ErrorOf(Experiment(jacobi, "[network]\nrounds = \"over_links\"\nround_timeout = -1.0\n")),
      AllOf(HasSubstr("net.toml:22: [network] round_timeout"), HasSubstr("[0, ")));
  // round_policy: "apply" | "hold", only with rounds over the links.
  EXPECT_EQ(over.network.round_policy, RoundPolicy::kApply);
  EXPECT_EQ(mjf::testing::Parse(Experiment(jacobi,
                                           "[network]\nrounds = \"over_links\"\n"
                                           "round_policy = \"hold\"\n"),
                                "net.toml")
                .network.round_policy,
            RoundPolicy::kHold);
  EXPECT_THAT(ErrorOf(Experiment(jacobi, "[network]\nround_policy = \"hold\"\n")),
              AllOf(HasSubstr("net.toml:21: [network] round_policy"), HasSubstr("over_links")));
  EXPECT_THAT(
      ErrorOf(Experiment(jacobi, "[network]\nrounds = \"over_links\"\nround_policy = \"wait\"\n")),
      AllOf(HasSubstr("net.toml:22: [network] round_policy"), HasSubstr("hold")));
  EXPECT_THAT(ErrorOf(Experiment(jacobi, "[network]\nrounds = \"over_links\"\nlatency = 0.001\n")),
              AllOf(HasSubstr("net.toml:22: [network] latency"), HasSubstr("one hop"),
                    HasSubstr("not one round fits a sample")));
  // The same latency instantaneously, or without rounds (last_input), is fine.
  EXPECT_EQ(ErrorOf(Experiment(jacobi, "[network]\nlatency = 0.001\n")), "");
  EXPECT_EQ(ErrorOf(Experiment(kPerAgent, "[network]\nrounds = \"over_links\"\nlatency = 0.001\n")),
            "");
  // The central solve's round is two hops of the leader links' star: an override counts, and is
  // named by its [[network.link]] line.
  EXPECT_THAT(ErrorOf(Experiment(central,
                                 "[network]\nrounds = \"over_links\"\n"
                                 "[[network.link]]\nfrom = 0\nto = 1\nlatency = 0.001\n")),
              AllOf(HasSubstr("net.toml:22: [network.link] latency"), HasSubstr("twice"),
                    HasSubstr("not one round fits a sample")));
  // A follower link's latency does not delay the central solve's rounds.
  EXPECT_EQ(ErrorOf(Experiment(central,
                               "[network]\nrounds = \"over_links\"\n"
                               "[[network.link]]\nfrom = 1\nto = 2\nlatency = 0.001\n")),
            "");
}

}  // namespace
}  // namespace mjf::runner
