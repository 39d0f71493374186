// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Receiver-side prediction ([execution] predict, docs/NETWORK.md): a received message
// carries the sender's state at the time it was measured; the receiver carries it over the
// message's age tau up to its own sample time before the law sees it, so that f_j, evaluated
// at the receiver's time, and the neighbour's state refer to the same instant.
// Pure: no MuJoCo.
#ifndef MJFORMATION_CONTROL_MESSAGE_PREDICTION_HPP_
#define MJFORMATION_CONTROL_MESSAGE_PREDICTION_HPP_

#include <mjformation/plugin.h>

#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/agent_clock.hpp"

namespace mjf::runner {

// Standard gravity, m/s^2: the hover thrust that the "attitude" prediction assumes.
inline constexpr double kPredictionGravity = 9.81;

// The horizontal acceleration (x, y, 0) the sender's attitude implies when its thrust holds
// altitude: g tan(tilt) along the tilt, i.e. g z_b,xy / z_b,z with z_b the body z axis.
void AttitudeAcceleration(const mjfVehicleState& state, double* acc);

// Propagates m->state by tau seconds (tau may be negative when the receiver's clock is behind
// the sender's): p += v tau + a tau^2 / 2, v += a tau, exact for model (40) (a double
// integrator) under zero-order hold when a is constant over the gap. a: the sender's input
// (kInput, NaN read as 0) or its attitude's acceleration (kAttitude). kNone: no change.
void PredictMessage(Predict mode, double tau, mjfMessage* m);

// A follower's inbox carried to its sample time before the law sees it; holds each follower's
// copy of the leader's message as predicted (the network's own copy stays as received).
class InboxPrediction {
 public:
  InboxPrediction(Predict mode, int n_followers) : mode_(mode), leader_held_(n_followers) {}

  // Predicts every message of follower's inbox (in place) and the leader's (into a copy held
  // here) over its age at time (s, the common time of the tick), read on the clocks that
  // stamped them; returns the leader's message to hand the law (the copy, or `leader` itself
  // when the mode is kNone; null stays null).
  const mjfMessage* PredictInbox(int follower, const AgentClocks& clocks, double time,
                                 std::vector<mjfMessage>* inbox, const mjfMessage* leader);

 private:
  Predict mode_;
  std::vector<mjfMessage> leader_held_;  // [follower]
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_MESSAGE_PREDICTION_HPP_
