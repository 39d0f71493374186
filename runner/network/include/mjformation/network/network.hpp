// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The simulated network of one swarm: every directed link (follower edge j -> i and leader link
// 0 -> i), the messages in flight on each, what each receiver holds (the newest message per
// in-link: an arriving message older than the one held is dropped), the range-limited topology
// and its spanning tree, and the age of the information each follower acts on. Pure: plain
// arrays in, plain arrays out, no MuJoCo. Vehicle 0 is the leader, 1..N the followers.
#ifndef MJFORMATION_NETWORK_NETWORK_HPP_
#define MJFORMATION_NETWORK_NETWORK_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/network/link.hpp"
#include "mjformation/network/message_state.hpp"
#include "mjformation/network/round_courier.hpp"

namespace mjf::network {

struct LinkSpec {
  int from = 0;  // sending vehicle (0: the leader)
  int to = 1;    // receiving follower vehicle, 1..N
  LinkParams params;
};

// A range-limited link appearing or disappearing.
struct TopologyEvent {
  double time = 0.0;  // s, first step at which the new state holds
  int from = 0, to = 0;
  bool up = false;
  template <typename Archive>
  void VisitState(Archive& archive) {
    archive(time, from, to, up);
  }
};

// Per-follower age of information (s): at each tick, now minus the send time of the oldest
// message the follower acts on (now when one of its in-links has delivered nothing yet).
struct AgeStats {
  double sum = 0.0;
  double max = 0.0;
  int64_t ticks = 0;
  double mean() const { return ticks > 0 ? sum / static_cast<double>(ticks) : 0.0; }
  template <typename Archive>
  void VisitState(Archive& archive) {
    archive(sum, max, ticks);
  }
};

class Network {
 public:
  // links: every directed link once; the order of a receiver's links is the order of its
  // messages. seed: the run's seed (each link draws from LinkSeed(seed, index)).
  Network(int n_followers, std::vector<LinkSpec> links, double timestep, uint64_t seed);

  // Range limits at `step` from the vehicles' positions ([vehicle] m); records topology
  // switches and the time without a directed spanning tree rooted at the leader. Call once per
  // step before Broadcast.
  void UpdateTopology(int64_t step, const std::vector<std::array<double, 3>>& positions);
  // `sender` hands `message` to each of its out-links that broadcasts at this step and exists.
  void Broadcast(int64_t step, int sender, const mjfMessage& message);
  // Delivers every message due at or before `step` (newer message wins) and updates the age
  // of information.
  void Deliver(int64_t step);

  // What follower vehicle `receiver` holds, newest per in-neighbour (leader excluded), packed
  // into `out` (cleared first); *leader: the leader's message or nullptr. With round >= 0, each
  // message carries the neighbour's round-`round` payload when that round message got through
  // (else its held payload and round).
  void Inbox(int receiver, int round, std::vector<mjfMessage>* out,
             const mjfMessage** leader) const;
  // `out` as Inbox(receiver, -1 or an earlier round) packed it in this tick, with only the round
  // part (round, n_payload, payload) of each message set for `round` as Inbox would set it: the
  // state and input parts (which the receiver may have predicted) are kept.
  void RefreshRound(int receiver, int round, std::vector<mjfMessage>* out) const;
  // A Jacobi round message from `sender` (loss only: see docs/NETWORK.md).
  void ExchangeRound(int sender, const mjfMessage& message);
  void ClearRounds();
  // Rounds over the links (rounds = "over_links"): `sender`'s round message of the sample taken
  // at sample_step, handed to each of its follower out-links that exists now (latency, jitter,
  // loss as a state message); CollectRounds appends those arriving at or before `step`
  // (letter.link: the link index, spec(link).to the receiver).
  void SendRound(int64_t step, int sender, int64_t sample_step, const mjfMessage& message);
  void CollectRounds(int64_t step, std::vector<RoundLetter>* out);

  int n_links() const { return static_cast<int>(links_.size()); }
  double timestep() const { return timestep_; }
  const LinkSpec& spec(int link) const { return specs_[link]; }
  const Link& link(int link) const { return links_[link]; }
  bool link_up(int link) const { return up_[link]; }
  const std::vector<TopologyEvent>& events() const { return events_; }
  bool has_spanning_tree() const { return spanning_; }
  double time_without_spanning_tree() const {
    return static_cast<double>(steps_without_tree_) * timestep_;
  }
  const AgeStats& age(int follower_vehicle) const { return age_[follower_vehicle]; }
  // The range topology's events, a list that grows with the run, walked by an archive that
  // stores lengths (a checkpoint's StateArchive), never by the fixed-length one.
  template <typename Archive>
  void VisitEvents(Archive& archive) {
    archive(events_);
  }
  // Drops the topology events recorded so far, for a host that reports none (the native MuJoCo
  // plugin: its state is plugin_state, and the list would only grow).
  void ForgetEvents() { events_.clear(); }

  // The most exchange-round letters in flight at once over all links ([network] rounds =
  // "over_links": RoundsOverLinks computes it); the fixed-length state holds that many. 0, the
  // default: no rounds travel, and the state holds none.
  void SetRoundCapacity(size_t letters) { rounds_in_flight_.SetCapacity(letters); }

  // Everything the network carries from step to step, of a length fixed by the links'
  // parameters (a fixed-length archive, message_state.hpp): each link's stream and counts, its
  // messages in flight (at most MaxInFlight), held and of this tick's round, the range
  // topology, the ages and the exchange-round letters in flight (at most SetRoundCapacity's).
  // Not walked: the topology events (VisitEvents), a list that grows with the run.
  template <typename Archive>
  void VisitState(Archive& archive) {
    for (size_t l = 0; l < links_.size(); ++l) {
      links_[l].VisitState(archive);
      VisitBounded(archive, in_flight_[l], static_cast<size_t>(capacity_[l]),
                   "a link's queue of messages in flight", [](Archive& a, InFlight& f) {
                     a(f.arrival_step, f.send_step);
                     VisitMessage(a, f.message);
                   });
    }
    VisitMessages(archive, held_);
    VisitMessages(archive, round_);
    for (std::vector<bool>* flags : {&up_, &has_held_, &has_round_}) VisitFlags(archive, *flags);
    archive(spanning_, topology_known_, steps_without_tree_, age_);
    rounds_in_flight_.VisitState(archive);
  }

 private:
  struct InFlight {
    int64_t arrival_step;
    int64_t send_step;
    mjfMessage message;
  };
  bool SpanningTree() const;

  int n_vehicles_;
  double timestep_;
  std::vector<LinkSpec> specs_;
  std::vector<Link> links_;
  std::vector<std::vector<int>> out_links_;  // [vehicle] links it sends on
  std::vector<std::vector<int>> in_links_;   // [vehicle] links it receives on, spec order
  std::vector<bool> up_;
  std::vector<std::vector<InFlight>> in_flight_;  // [link]
  std::vector<int64_t> capacity_;                 // [link] MaxInFlight of its parameters
  std::vector<mjfMessage> held_;                  // [link]
  std::vector<bool> has_held_;
  std::vector<mjfMessage> round_;  // [link] the last round message that got through
  std::vector<bool> has_round_;
  RoundCourier rounds_in_flight_;
  std::vector<TopologyEvent> events_;
  bool spanning_ = true;
  bool topology_known_ = false;
  int64_t steps_without_tree_ = 0;
  std::vector<AgeStats> age_;  // [vehicle]
};

}  // namespace mjf::network

#endif  // MJFORMATION_NETWORK_NETWORK_HPP_
