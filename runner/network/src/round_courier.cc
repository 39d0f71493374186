// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/network/round_courier.hpp"

#include <algorithm>

#include "mjformation/time_steps.hpp"

namespace mjf::network {

int64_t MaxRoundLettersInFlight(const LinkParams& params, double timestep, int64_t per_sample,
                                int64_t period_steps) {
  // Letters in flight after step k were sent in (k - D, k]; the sample periods that window
  // meets, a period shortened by one step by a drifting clock included, each sent per_sample.
  const int64_t longest = StepsAtOrAfter(params.latency + params.jitter, timestep);
  const int64_t shortest_period = std::max<int64_t>(period_steps - 1, 1);
  return per_sample * (longest / shortest_period + 2);
}

void RoundCourier::Post(Link& link, int link_index, int64_t step, int64_t sample_step,
                        const mjfMessage& message) {
  if (auto arrival = link.TransmitRoundDelayed(step)) {
    in_flight_.push_back({link_index, sample_step, step, *arrival, message});
  }
}

void RoundCourier::Collect(int64_t step, std::vector<Link>& links, std::vector<RoundLetter>* out) {
  size_t kept = 0;
  for (size_t k = 0; k < in_flight_.size(); ++k) {
    if (in_flight_[k].arrival_step > step) {
      if (kept != k) in_flight_[kept] = in_flight_[k];
      ++kept;
      continue;
    }
    // Delivered at this step (a letter due earlier was collected then: Collect runs every step).
    in_flight_[k].arrival_step = step;
    links[in_flight_[k].link].RecordRoundDelivery(in_flight_[k].send_step, step);
    out->push_back(in_flight_[k]);
  }
  in_flight_.resize(kept);
}

}  // namespace mjf::network
