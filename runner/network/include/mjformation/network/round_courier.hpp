// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Exchange-round messages in flight ([network] rounds = "over_links"): a Jacobi
// iterate w_j, a central solve's R_i on its way to the solver or W_i on its way back, each
// handed to a Link at a physics step and collected at the step it arrives (latency + jitter,
// loss, as a state message). Unlike state messages, nothing is held per link and no newer round
// replaces an older one: every round message that arrives is handed out, tagged with the sample
// it belongs to, and the receiver decides whether it still needs it. Pure: no MuJoCo.
#ifndef MJFORMATION_NETWORK_ROUND_COURIER_HPP_
#define MJFORMATION_NETWORK_ROUND_COURIER_HPP_

#include <mjformation/plugin.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mjformation/network/link.hpp"
#include "mjformation/network/message_state.hpp"

namespace mjf::network {

struct RoundLetter {
  int link = 0;              // index of the link it travelled on (the poster's numbering)
  int64_t sample_step = 0;   // the sample its round belongs to (its physics step; the central
                             // solve: the sender's sample index)
  int64_t send_step = 0;     // when it was handed to the link
  int64_t arrival_step = 0;  // when it arrived
  mjfMessage message{};      // round in message.round, the iterate in its payload
};

// The most round letters one link can have in flight between two steps: `per_sample` letters a
// sample, all sent within the sample's period (`period_steps`: the next sample ends the
// exchange), each in flight for at most the link's longest delay (latency + jitter).
int64_t MaxRoundLettersInFlight(const LinkParams& params, double timestep, int64_t per_sample,
                                int64_t period_steps);

class RoundCourier {
 public:
  // At most `letters` in flight at once: the bound the fixed-length state holds (a caller that
  // knows the rounds per sample and the sample period computes it); 0, the default: the courier
  // is not in the state.
  void SetCapacity(size_t letters) { capacity_ = letters; }
  size_t capacity() const { return capacity_; }
  // Hands `message` (a round of the sample taken at sample_step) to `link` at `step`; a letter
  // the loss model drops is counted on the link and never arrives.
  void Post(Link& link, int link_index, int64_t step, int64_t sample_step,
            const mjfMessage& message);
  // Moves every letter due at or before `step` to *out (appended, in posting order) and records
  // its delivery on its link (`links[letter.link]`).
  void Collect(int64_t step, std::vector<Link>& links, std::vector<RoundLetter>* out);
  bool empty() const { return in_flight_.empty(); }

  // The letters in flight, in posting order (which is their delivery order within a step), as
  // a bounded queue of capacity() slots (message_state.hpp); nothing when the capacity is 0.
  template <typename Archive>
  void VisitState(Archive& archive) {
    if (capacity_ == 0) return;
    VisitBounded(archive, in_flight_, capacity_, "the exchange-round letters in flight",
                 [](Archive& a, RoundLetter& letter) {
                   a(letter.link, letter.sample_step, letter.send_step, letter.arrival_step);
                   VisitMessage(a, letter.message);
                 });
  }

 private:
  std::vector<RoundLetter> in_flight_;
  size_t capacity_ = 0;
};

}  // namespace mjf::network

#endif  // MJFORMATION_NETWORK_ROUND_COURIER_HPP_
