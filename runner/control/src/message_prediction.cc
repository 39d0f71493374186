// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/message_prediction.hpp"

#include <cmath>

namespace mjf::runner {

void AttitudeAcceleration(const mjfVehicleState& state, double* acc) {
  const double w = state.quat[0], x = state.quat[1], y = state.quat[2], z = state.quat[3];
  // Third column of the rotation matrix of the unit quaternion (w, x, y, z): the body z axis.
  const double zx = 2.0 * (x * z + w * y);
  const double zy = 2.0 * (y * z - w * x);
  const double zz = 1.0 - 2.0 * (x * x + y * y);
  // Thrust T z_b with T z_b,z = g (altitude held): horizontal acceleration g z_b,xy / z_b,z.
  const bool upright = zz > 1e-3;  // a vehicle on its side implies nothing usable
  acc[0] = upright ? kPredictionGravity * zx / zz : 0.0;
  acc[1] = upright ? kPredictionGravity * zy / zz : 0.0;
  acc[2] = 0.0;
}

void PredictMessage(Predict mode, double tau, mjfMessage* m) {
  if (mode == Predict::kNone) return;
  double acc[3] = {0.0, 0.0, 0.0};
  if (mode == Predict::kAttitude) {
    AttitudeAcceleration(m->state, acc);
  } else {
    for (int k = 0; k < 3; ++k) acc[k] = std::isfinite(m->input[k]) ? m->input[k] : 0.0;
  }
  for (int k = 0; k < 3; ++k) {
    // Model (40) over a gap tau under zero-order hold: x(t + tau) = A(tau) x(t) + B(tau) a.
    m->state.pos[k] += m->state.vel[k] * tau + 0.5 * acc[k] * tau * tau;
    m->state.vel[k] += acc[k] * tau;
  }
}

// tau = c_i(now) - c_j(send time) (no common clock); with synchronised clocks both read the
// common time and tau is the message's true age.
const mjfMessage* InboxPrediction::PredictInbox(int follower, const AgentClocks& clocks,
                                                double time, std::vector<mjfMessage>* inbox,
                                                const mjfMessage* leader) {
  if (mode_ == Predict::kNone) return leader;
  const double now = clocks.Reading(follower + 1, time);
  for (mjfMessage& m : *inbox) {
    PredictMessage(mode_, now - clocks.Reading(m.sender, m.send_time), &m);
  }
  if (!leader) return nullptr;
  leader_held_[follower] = *leader;
  PredictMessage(mode_, now - leader->send_time, &leader_held_[follower]);
  return &leader_held_[follower];
}

}  // namespace mjf::runner
