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

#include <cstdint>
#include <vector>

#include "mjformation/network/link.hpp"

namespace mjf::network {

struct RoundLetter {
  int link = 0;              // index of the link it travelled on (the poster's numbering)
  int64_t sample_step = 0;   // the sample its round belongs to (its physics step; the central
                             // solve: the sender's sample index)
  int64_t send_step = 0;     // when it was handed to the link
  int64_t arrival_step = 0;  // when it arrived
  mjfMessage message{};      // round in message.round, the iterate in its payload
};

class RoundCourier {
 public:
  // Hands `message` (a round of the sample taken at sample_step) to `link` at `step`; a letter
  // the loss model drops is counted on the link and never arrives.
  void Post(Link& link, int link_index, int64_t step, int64_t sample_step,
            const mjfMessage& message);
  // Moves every letter due at or before `step` to *out (appended, in posting order) and records
  // its delivery on its link (`links[letter.link]`).
  void Collect(int64_t step, std::vector<Link>& links, std::vector<RoundLetter>* out);
  bool empty() const { return in_flight_.empty(); }

 private:
  std::vector<RoundLetter> in_flight_;
};

}  // namespace mjf::network

#endif  // MJFORMATION_NETWORK_ROUND_COURIER_HPP_
