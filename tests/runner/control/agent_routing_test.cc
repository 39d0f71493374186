// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The channel's routing: the links in each follower's message order with their overrides, the
// neighbourhood handed to create(), a broadcast delivered to the in-neighbours only, the
// outgoing message and the age of information at samples.
#include "mjformation/control/agent_routing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mjformation/formation/graph.hpp"

namespace mjf::runner {
namespace {

// Leader -> 1, 1 -> 2, 3 -> 2, 2 -> 3 (0-based followers 0, 1, 2).
formation::Graph Triangle() {
  return formation::Graph(3, {1.0, 0.0, 0.0}, {{0, 1}, {2, 1}, {1, 2}});
}

std::vector<mjfVehicleState> States(int n) {
  std::vector<mjfVehicleState> s(n);
  for (int v = 0; v < n; ++v) s[v].pos[0] = 10.0 * v;
  return s;
}

TEST(AgentRoutingTest, LinksFollowEachFollowersMessagesThenItsLeaderLinkWithOverrides) {
  NetworkConfig c;
  c.defaults.latency = 0.01;
  c.links.push_back({3, 2, 0, {}});
  c.links.back().params.latency = 0.05;
  const std::vector<network::LinkSpec> links = AgentRouting::Links(Triangle(), c);
  ASSERT_EQ(links.size(), 4u);
  EXPECT_EQ(links[0].from, 0);  // follower 1 hears only the leader
  EXPECT_EQ(links[0].to, 1);
  EXPECT_EQ(links[1].from, 1);  // follower 2: its in-neighbours 1 and 3
  EXPECT_EQ(links[2].from, 3);
  EXPECT_EQ(links[2].to, 2);
  EXPECT_DOUBLE_EQ(links[2].params.latency, 0.05);
  EXPECT_DOUBLE_EQ(links[1].params.latency, 0.01);
  EXPECT_EQ(links[3].from, 2);
  EXPECT_EQ(links[3].to, 3);
}

TEST(AgentRoutingTest, NeighbourhoodIsTheFollowersRowOfTheGraph) {
  const AgentRouting routing(Triangle(), NetworkConfig{}, 1, 0.001, 1);
  const mjfNeighbourhood& n = routing.neighbourhood(1);
  EXPECT_EQ(n.follower, 1);
  EXPECT_EQ(n.n_followers, 3);
  EXPECT_DOUBLE_EQ(n.leader_weight, 0.0);
  ASSERT_EQ(n.n_neighbours, 2);
  EXPECT_EQ(n.neighbours[0], 0);
  EXPECT_EQ(n.neighbours[1], 2);
  EXPECT_DOUBLE_EQ(routing.neighbourhood(0).leader_weight, 1.0);
}

TEST(AgentRoutingTest, ABroadcastReachesTheInNeighboursOnlyWithStateAndInput) {
  AgentRouting routing(Triangle(), NetworkConfig{}, 1, 0.001, 1);
  const std::vector<mjfVehicleState> states = States(4);
  std::vector<mjfSetpoint> setpoints(4);
  for (int v = 0; v < 4; ++v) setpoints[v].acc[0] = 0.5 * v;
  routing.BeginTick(0, 0.0, states, states, setpoints);
  const mjfMessage* leader = routing.FetchInbox(1, -1);
  EXPECT_EQ(leader, nullptr);  // follower 2 has no leader link
  const std::vector<mjfMessage>& inbox = routing.inbox(1);
  ASSERT_EQ(inbox.size(), 2u);
  EXPECT_EQ(inbox[0].sender, 1);
  EXPECT_EQ(inbox[1].sender, 3);
  EXPECT_DOUBLE_EQ(inbox[1].state.pos[0], 30.0);
  EXPECT_DOUBLE_EQ(inbox[1].input[0], 1.5);  // the sender's last u on the bus
  leader = routing.FetchInbox(0, -1);
  ASSERT_NE(leader, nullptr);
  EXPECT_EQ(leader->sender, 0);
  EXPECT_TRUE(routing.inbox(0).empty());
  EXPECT_DOUBLE_EQ(routing.self(2).pos[0], 30.0);
}

TEST(AgentRoutingTest, OutgoingIsOpenedPerRoundAndFilledFromTheBus) {
  AgentRouting routing(Triangle(), NetworkConfig{}, 2, 0.001, 1);
  EXPECT_TRUE(std::isnan(routing.outgoing(0).input[0]));  // nothing written yet
  const std::vector<mjfVehicleState> states = States(4);
  std::vector<mjfSetpoint> setpoints(4);
  setpoints[2].acc[1] = -2.0;
  routing.BeginTick(7, 0.007, states, states, setpoints);
  mjfMessage* out = routing.OpenOutgoing(1, 1);
  out->n_payload = 3;
  out = routing.OpenOutgoing(1, 1);
  EXPECT_EQ(out->round, 1);
  EXPECT_EQ(out->n_payload, 0);
  routing.FillOutgoing(1, setpoints);
  EXPECT_EQ(out->sender, 2);
  EXPECT_DOUBLE_EQ(out->send_time, 0.007);
  EXPECT_DOUBLE_EQ(out->state.pos[0], 20.0);
  EXPECT_DOUBLE_EQ(out->input[1], -2.0);
}

TEST(AgentRoutingTest, SampleAgeCountsOnlyFollowersThatWroteAPayload) {
  NetworkConfig c;
  c.defaults.latency = 0.002;
  AgentRouting routing(Triangle(), c, 1, 0.001, 1);
  const std::vector<mjfVehicleState> states = States(4);
  const std::vector<mjfSetpoint> setpoints(4);
  for (int64_t step = 0; step <= 5; ++step) {
    routing.BeginTick(step, 0.001 * static_cast<double>(step), states, states, setpoints);
    routing.FetchInbox(1, -1);
    routing.OpenOutgoing(1, 0)->n_payload = step == 5 ? 1 : 0;
  }
  routing.RecordSampleAge();
  EXPECT_EQ(routing.sample_age(1).ticks, 1);
  EXPECT_NEAR(routing.sample_age(1).max, 0.002, 1e-12);  // the messages are two steps old
  EXPECT_EQ(routing.sample_age(0).ticks, 0);
}

}  // namespace
}  // namespace mjf::runner
