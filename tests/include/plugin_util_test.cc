// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What every formation law reads of its input: the planar state of a vehicle, and a per-agent
// law's inbox (which message is whose, when the law has heard enough, the leader's state from
// its own link or a neighbour's relay).
#include "mjformation/plugin_util.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mjf::plugin {
namespace {

mjfVehicleState State(double px, double py, double vx, double vy) {
  mjfVehicleState s{};
  s.pos[0] = px;
  s.pos[1] = py;
  s.pos[2] = 7.0;  // not planar: never read
  s.vel[0] = vx;
  s.vel[1] = vy;
  s.vel[2] = -7.0;
  return s;
}

mjfMessage Message(int sender, const mjfVehicleState& state) {
  mjfMessage m{};
  m.sender = sender;
  m.state = state;
  return m;
}

mjfAgentInput Input(const std::vector<mjfMessage>& messages, const mjfMessage* leader) {
  mjfAgentInput in{};
  in.n_messages = static_cast<int>(messages.size());
  in.messages = messages.data();
  in.leader = leader;
  return in;
}

TEST(PluginUtilTest, ReadPlanarPvTakesHorizontalPositionThenVelocity) {
  double pv[4] = {0, 0, 0, 0};
  ReadPlanarPv(State(1.5, -2.0, 0.25, 3.0), pv);
  EXPECT_EQ(pv[0], 1.5);
  EXPECT_EQ(pv[1], -2.0);
  EXPECT_EQ(pv[2], 0.25);
  EXPECT_EQ(pv[3], 3.0);
}

TEST(PluginUtilTest, InboxMatchesEachNeighbourToItsSender) {
  NeighbourInbox inbox({2, 0});  // followers 2 and 0: senders 3 and 1
  const std::vector<mjfMessage> messages = {
      Message(1, State(1, 0, 0, 0)), Message(2, State(2, 0, 0, 0)), Message(3, State(3, 0, 0, 0))};
  EXPECT_TRUE(inbox.Gather(Input(messages, nullptr), 0.0));
  ASSERT_NE(inbox.message(0), nullptr);
  ASSERT_NE(inbox.message(1), nullptr);
  EXPECT_EQ(inbox.message(0)->sender, 3);
  EXPECT_EQ(inbox.message(1)->sender, 1);
  EXPECT_FALSE(inbox.knows_leader());  // no leader link, no relay
}

TEST(PluginUtilTest, InboxWaitsForEveryNeighbour) {
  NeighbourInbox inbox({0, 1});
  const std::vector<mjfMessage> messages = {Message(2, State(0, 0, 0, 0))};
  EXPECT_FALSE(inbox.Gather(Input(messages, nullptr), 0.0));
  EXPECT_EQ(inbox.message(0), nullptr);
  EXPECT_NE(inbox.message(1), nullptr);
  // The next call starts afresh: a message is not carried over from the call before.
  EXPECT_FALSE(inbox.Gather(Input({}, nullptr), 0.0));
  EXPECT_EQ(inbox.message(1), nullptr);
}

TEST(PluginUtilTest, InboxWithALeaderLinkWaitsForTheLeadersOwnMessage) {
  NeighbourInbox inbox({0});
  const std::vector<mjfMessage> messages = {Message(1, State(0, 0, 0, 0))};
  EXPECT_FALSE(inbox.Gather(Input(messages, nullptr), 0.5));  // a_i0 > 0, no leader message
  const mjfMessage leader = Message(0, State(10, 20, 1, 2));
  EXPECT_TRUE(inbox.Gather(Input(messages, &leader), 0.5));
  ASSERT_TRUE(inbox.knows_leader());
  EXPECT_EQ(inbox.leader_pv()[0], 10);
  EXPECT_EQ(inbox.leader_pv()[1], 20);
  EXPECT_EQ(inbox.leader_pv()[2], 1);
  EXPECT_EQ(inbox.leader_pv()[3], 2);
}

TEST(PluginUtilTest, InboxTakesTheLeaderFromARelayAndKeepsIt) {
  NeighbourInbox inbox({0, 1});
  std::vector<mjfMessage> messages = {Message(1, State(0, 0, 0, 0)), Message(2, State(0, 0, 0, 0))};
  messages[0].n_payload = kPayloadUsed - 1;  // too short to carry the relay: passed over
  messages[0].payload[kPayloadLeader] = -1.0;
  messages[1].n_payload = kPayloadUsed;
  const double relayed[4] = {4, 5, 6, 7};
  for (int k = 0; k < 4; ++k) messages[1].payload[kPayloadLeader + k] = relayed[k];
  EXPECT_TRUE(inbox.Gather(Input(messages, nullptr), 0.0));
  ASSERT_TRUE(inbox.knows_leader());
  for (int k = 0; k < 4; ++k) EXPECT_EQ(inbox.leader_pv()[k], relayed[k]);
  // Heard once, the leader's state is kept when a later call brings none.
  EXPECT_FALSE(inbox.Gather(Input({}, nullptr), 0.0));
  EXPECT_TRUE(inbox.knows_leader());
  EXPECT_EQ(inbox.leader_pv()[0], 4);
}

}  // namespace
}  // namespace mjf::plugin
