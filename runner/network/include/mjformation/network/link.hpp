// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One simulated radio link (a directed follower edge j -> i, or the leader's link 0 -> i): what
// happens to a message handed to it at a physics step. Pure: no MuJoCo, no clock but the step
// index. Every random draw comes from the link's own std::mt19937_64, turned into numbers by our
// own transforms (never std::*_distribution, whose output differs between standard libraries),
// so the same seed gives the same bytes on every platform and links never share a stream.
#ifndef MJFORMATION_NETWORK_LINK_HPP_
#define MJFORMATION_NETWORK_LINK_HPP_

#include <cstdint>
#include <optional>
#include <random>

#include "mjformation/network/link_params.hpp"

namespace mjf::network {

// Seeded uniform draws in [0, 1) from the 53 high bits of mt19937_64 (platform-stable).
class Random {
 public:
  explicit Random(uint64_t seed) : engine_(seed) {}
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  bool Bernoulli(double p) { return Uniform() < p; }
  template <typename Archive>
  void VisitState(Archive& archive) {
    archive(engine_);
  }

 private:
  std::mt19937_64 engine_;
};

// A well-mixed per-link seed from the run's seed and the link's index (SplitMix64 finaliser).
uint64_t LinkSeed(uint64_t run_seed, uint64_t link_index);

// Counts of one link over a run.
struct LinkStats {
  int64_t sent = 0;          // messages handed to the link while it existed
  int64_t lost = 0;          // dropped by the loss model
  int64_t delivered = 0;     // reached the receiver (including ones then found stale)
  int64_t stale = 0;         // arrived older than the message already held: dropped
  int64_t out_of_range = 0;  // broadcasts while the link did not exist (range limit)
  double latency_sum = 0.0;  // s, over delivered messages (arrival time - send time)
  double latency_max = 0.0;
  int64_t rounds_sent = 0;  // exchange-round messages (Jacobi iterates; over links: also R_i, W_i)
  int64_t rounds_lost = 0;
  // Rounds carried over the link ([network] rounds = "over_links"): delivered, and their delay.
  int64_t rounds_delivered = 0;
  double round_latency_sum = 0.0;  // s
  double round_latency_max = 0.0;

  template <typename Archive>
  void VisitState(Archive& archive) {
    archive(sent, lost, delivered, stale, out_of_range, latency_sum, latency_max, rounds_sent,
            rounds_lost, rounds_delivered, round_latency_sum, round_latency_max);
  }
};

// The most messages one link can have in flight between two steps: one per broadcast within
// the longest delay, latency + jitter, in whole steps (a fixed-length state holds that many).
int64_t MaxInFlight(const LinkParams& params, double timestep);

class Link {
 public:
  // timestep: the physics step dt (s). Throws std::invalid_argument on parameters that are not
  // physical (the config layer reports them with file and line first).
  Link(const LinkParams& params, double timestep, uint64_t seed);

  const LinkParams& params() const { return params_; }
  double timestep() const { return timestep_; }  // s, the physics step
  // Whether the sender broadcasts over this link at `step` (the link's rate).
  bool Broadcasts(int64_t step) const { return step % params_.period_steps == 0; }
  // A message sent at `send_step`: the physics step at which it is delivered (the first step
  // whose time is >= send time + latency + jitter draw), or nothing when the loss model drops
  // it. Draw order per message: one uniform for the loss, then (if delivered and jitter > 0)
  // one for the jitter.
  std::optional<int64_t> Transmit(int64_t send_step);
  // Loss only (a Jacobi round inside one sample: see docs/NETWORK.md); true when delivered.
  bool TransmitRound();
  // An exchange-round message carried like a state message (rounds = "over_links"): the step
  // it arrives at, or nothing when lost. The same draws as Transmit (loss, then jitter), counted
  // as a round message.
  std::optional<int64_t> TransmitRoundDelayed(int64_t send_step);
  void RecordRoundDelivery(int64_t send_step, int64_t arrival_step);
  // Records a delivery at `arrival_step` of a message sent at `send_step` (stale: dropped).
  void RecordDelivery(int64_t send_step, int64_t arrival_step, bool stale);
  void RecordOutOfRange() { ++stats_.out_of_range; }

  const LinkStats& stats() const { return stats_; }
  bool in_bad_state() const { return bad_; }

  // What the link carries from step to step: its random stream (none on an ideal link, which
  // draws nothing), its Gilbert-Elliott state and its counts.
  template <typename Archive>
  void VisitState(Archive& archive) {
    if (!ideal_) archive(random_);
    archive(bad_, stats_);
  }

 private:
  bool DrawLoss();
  // The arrival step of a message sent at send_step and not lost (draws the jitter).
  int64_t ArrivalStep(int64_t send_step);

  LinkParams params_;
  double timestep_;
  Random random_;
  // A lossless, jitter-free link draws nothing that matters: its loss draw always passes and its
  // stream feeds nothing else, so it skips the draw (the same messages, the same bytes) and
  // its delay is a fixed number of steps.
  bool ideal_;
  int64_t fixed_delay_steps_;
  bool bad_ = false;  // Gilbert-Elliott channel state
  LinkStats stats_;
};

}  // namespace mjf::network

#endif  // MJFORMATION_NETWORK_LINK_HPP_
