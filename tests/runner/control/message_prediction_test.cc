// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Receiver-side prediction: exact for a double integrator under zero-order hold, and
// the attitude form reads the acceleration a tilt implies.
#include "mjformation/control/message_prediction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mjf::runner {
namespace {

mjfMessage Sent(double px, double vx, double ux) {
  mjfMessage m{};
  m.state.pos[0] = px;
  m.state.vel[0] = vx;
  m.state.pos[1] = -2.0;
  m.state.vel[1] = 0.5;
  m.state.quat[0] = 1.0;
  m.input[0] = ux;
  m.input[1] = -0.3;
  m.input[2] = 0.0;
  return m;
}

// A double integrator stepped by its exact ZOH map over many small steps (the way the
// neighbour really moved while its message was in flight) ends where one prediction puts it.
TEST(MessagePredictionTest, ExactForADoubleIntegratorUnderZeroOrderHold) {
  for (double tau : {0.0, 0.001, 0.0137, 0.049, 0.2}) {
    mjfMessage m = Sent(3.0, -1.25, 0.8);
    double p[2] = {m.state.pos[0], m.state.pos[1]}, v[2] = {m.state.vel[0], m.state.vel[1]};
    const int n = 1000;
    const double h = tau / n;
    for (int k = 0; k < n; ++k) {
      for (int a = 0; a < 2; ++a) {
        p[a] += v[a] * h + 0.5 * m.input[a] * h * h;
        v[a] += m.input[a] * h;
      }
    }
    PredictMessage(Predict::kInput, tau, &m);
    for (int a = 0; a < 2; ++a) {
      EXPECT_NEAR(m.state.pos[a], p[a], 1e-12) << "tau " << tau;
      EXPECT_NEAR(m.state.vel[a], v[a], 1e-12) << "tau " << tau;
    }
  }
}

TEST(MessagePredictionTest, NoneLeavesTheMessageAndNaNInputIsZero) {
  mjfMessage m = Sent(3.0, -1.25, std::nan(""));
  PredictMessage(Predict::kNone, 0.1, &m);
  EXPECT_EQ(m.state.pos[0], 3.0);
  PredictMessage(Predict::kInput, 0.1, &m);  // no input yet: constant velocity
  EXPECT_DOUBLE_EQ(m.state.pos[0], 3.0 - 0.125);
  EXPECT_DOUBLE_EQ(m.state.vel[0], -1.25);
}

TEST(MessagePredictionTest, AttitudeGivesTheTiltsAcceleration) {
  mjfMessage m = Sent(0.0, 0.0, 5.0);  // the commanded input is ignored
  const double tilt = 0.2;             // pitch about +y: the thrust leans towards +x
  m.state.quat[0] = std::cos(tilt / 2);
  m.state.quat[2] = std::sin(tilt / 2);
  double acc[3];
  AttitudeAcceleration(m.state, acc);
  EXPECT_NEAR(acc[0], kPredictionGravity * std::tan(tilt), 1e-12);
  EXPECT_NEAR(acc[1], 0.0, 1e-12);
  PredictMessage(Predict::kAttitude, 0.1, &m);
  EXPECT_NEAR(m.state.vel[0], 0.1 * kPredictionGravity * std::tan(tilt), 1e-12);
}

// A follower's inbox is carried over each message's age on the clocks that stamped it, the
// leader's into a copy (the network's stays as received); kNone hands everything on untouched.
TEST(MessagePredictionTest, InboxPredictionCarriesTheInboxAndACopyOfTheLeaders) {
  const AgentClocks clocks(2, 0.0, 0.0, 0.001, 1);  // in phase: the common time
  std::vector<mjfMessage> inbox = {Sent(1.0, 2.0, 0.0)};
  inbox[0].sender = 2;
  inbox[0].send_time = 0.4;
  mjfMessage leader = Sent(0.0, 1.0, 0.0);
  leader.send_time = 0.3;
  InboxPrediction none(Predict::kNone, 2);
  EXPECT_EQ(none.PredictInbox(0, clocks, 0.5, &inbox, &leader), &leader);
  EXPECT_EQ(inbox[0].state.pos[0], 1.0);
  InboxPrediction input(Predict::kInput, 2);
  const mjfMessage* held = input.PredictInbox(0, clocks, 0.5, &inbox, &leader);
  EXPECT_DOUBLE_EQ(inbox[0].state.pos[0], 1.0 + 2.0 * 0.1);  // 0.1 s old at 2 m/s
  ASSERT_NE(held, nullptr);
  EXPECT_NE(held, &leader);
  EXPECT_DOUBLE_EQ(held->state.pos[0], 0.2);  // 0.2 s old at 1 m/s
  EXPECT_EQ(leader.state.pos[0], 0.0);
  EXPECT_EQ(input.PredictInbox(1, clocks, 0.5, &inbox, nullptr), nullptr);
}

}  // namespace
}  // namespace mjf::runner
