// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The host-plugin contract: each key lands in its typed field, other keys are the plugin's own,
// attribute texts count only as whole finite numbers, and a law's report round-trips.
#include "mjformation/plugin_contract.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace mjf::plugin::contract {
namespace {

TEST(PluginContractTest, ALawReportFillsItsFields) {
  Law law;
  EXPECT_FALSE(law.HasDelayMargin());
  EXPECT_TRUE(SetReported(law, "period", 0.02));
  EXPECT_TRUE(SetReported(law, "q", 5.0));
  EXPECT_TRUE(SetReported(law, "delta", 0.3));
  EXPECT_FALSE(SetReported(law, "error_bound", 1.0));  // the plugin's own key
  EXPECT_EQ(law.period, 0.02);
  EXPECT_EQ(law.q, 5.0);
  EXPECT_EQ(law.delta, 0.3);
  EXPECT_TRUE(law.HasDelayMargin());
  EXPECT_FALSE(law.HasInputBounds());
}

TEST(PluginContractTest, AttributesCountOnlyAsWholeFiniteNumbers) {
  Law law;
  EXPECT_TRUE(SetAttribute(law, "u_min", "-2.5"));
  EXPECT_FALSE(SetAttribute(law, "u_max", "3 m/s^2"));
  EXPECT_FALSE(SetAttribute(law, "u_max", "inf"));
  EXPECT_FALSE(SetAttribute(law, "rho", "1"));
  EXPECT_FALSE(law.HasInputBounds());
  EXPECT_TRUE(SetAttribute(law, "u_max", "3"));
  EXPECT_TRUE(law.HasInputBounds());
  EXPECT_EQ(law.u_min, -2.5);
  Guidance leader;
  EXPECT_TRUE(SetAttribute(leader, "a_min", "-1"));
  EXPECT_TRUE(SetAttribute(leader, "a_max", "1"));
  EXPECT_TRUE(leader.HasBounds());
}

TEST(PluginContractTest, AnAttitudeReportFillsItsFields) {
  Attitude a;
  EXPECT_TRUE(SetReported(a, "att_bw", 8.0));
  EXPECT_TRUE(SetReported(a, "att_bw_unlimited", 12.0));
  EXPECT_TRUE(SetReported(a, "tilt_max", 0.5));
  EXPECT_FALSE(SetReported(a, "kp_att", 1.0));
  EXPECT_EQ(a.att_bw, 8.0);
  EXPECT_EQ(a.att_bw_unlimited, 12.0);
  EXPECT_EQ(a.tilt_max, 0.5);
}

TEST(PluginContractTest, EmitWritesWhatTheHostReadsBack) {
  Law written;
  written.period = 0.05;
  written.q = 4.0;  // delta left unset: not emitted
  std::vector<std::pair<std::string, double>> report;
  Emit(
      written,
      [](void* user, const char* key, double value) {
        static_cast<std::vector<std::pair<std::string, double>>*>(user)->emplace_back(key, value);
      },
      &report);
  ASSERT_EQ(report.size(), 2u);
  Law read;
  for (const auto& [key, value] : report) EXPECT_TRUE(SetReported(read, key.c_str(), value));
  EXPECT_EQ(read.period, 0.05);
  EXPECT_EQ(read.q, 4.0);
  EXPECT_TRUE(std::isnan(read.delta));
}

TEST(PluginContractTest, TheAgentVersionIsNamedBySuffix) {
  EXPECT_EQ(AgentName("smc_discrete"), "smc_discrete_agent");
}

}  // namespace
}  // namespace mjf::plugin::contract
