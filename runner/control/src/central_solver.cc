// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/central_solver.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mjformation/control/errors.hpp"
#include "mjformation/formation/graph.hpp"

namespace mjf::runner {

CentralSolver::CentralSolver(const formation::Graph& graph)
    : n_followers_(graph.num_followers()),
      solver_(graph.laplacian_h()),
      rhs_(graph.num_followers(), 2),
      solved_(2 * static_cast<size_t>(graph.num_followers()), 0.0) {}

void CentralSolver::SolveRightHandSide() {
  solver_.SolveInPlace(rhs_);
  for (int i = 0; i < n_followers_; ++i) {
    solved_[2 * i] = rhs_(i, 0);
    solved_[2 * i + 1] = rhs_(i, 1);
  }
}

// A follower that has not yet heard every in-neighbour (loss or latency at start-up) does not
// sample and publishes nothing (n_payload = 0); the system cannot be solved without its row, so
// that sample gets no solution and every follower closes its loop with the last inputs, as under
// last_input (counted in summary.json: network.central_solve_skipped_samples).
void CentralSolver::SolvePublished(const std::vector<mjfMessage>& outgoing, double time) {
  int sampled = 0;
  int published = 0;
  for (int i = 0; i < n_followers_; ++i) {
    sampled += outgoing[i].n_payload > 0 ? 1 : 0;
    published += outgoing[i].n_payload >= 4 ? 1 : 0;
  }
  if (sampled == 0) return;  // between samples
  if (published != sampled) {
    throw SimulationError(
        fmt::format("t = {:.3f} s: coupling = \"central_solve\": {} of {} followers that sampled "
                    "published R_i (payload[2..3]) in round 0; the plugin does not support the "
                    "central solve",
                    time, published, sampled));
  }
  if (published != n_followers_) {
    ++skipped_samples_;
    return;
  }
  for (int i = 0; i < n_followers_; ++i) {
    rhs_(i, 0) = outgoing[i].payload[2];
    rhs_(i, 1) = outgoing[i].payload[3];
  }
  SolveRightHandSide();
  have_solution_ = true;
}

// Follower i's link pair takes its leader link's parameters when it has one, else the defaults;
// a range limit does not apply (the star is not the graph).
void CentralSolver::SetUpStar(const network::Network& network, const network::LinkParams& defaults,
                              uint64_t seed) {
  has_.assign(n_followers_, 0);
  rows_.assign(2 * static_cast<size_t>(n_followers_), 0.0);
  up_late_.assign(n_followers_, 0);
  down_late_.assign(n_followers_, 0);
  for (int i = 0; i < n_followers_; ++i) {
    network::LinkParams params = defaults;
    for (int l = 0; l < network.n_links(); ++l) {
      if (network.spec(l).from == 0 && network.spec(l).to == i + 1) params = network.spec(l).params;
    }
    params.range = 0.0;
    const auto base = static_cast<uint64_t>(network.n_links());
    up_.emplace_back(params, network.timestep(), network::LinkSeed(seed, base + i));
    down_.emplace_back(params, network.timestep(),
                       network::LinkSeed(seed, base + n_followers_ + i));
  }
}

void CentralSolver::SetStarCapacity(int64_t per_sample, int64_t period_steps) {
  int64_t up = 0, down = 0;
  for (int i = 0; i < n_followers_; ++i) {
    up += network::MaxRoundLettersInFlight(up_[i].params(), up_[i].timestep(), per_sample,
                                           period_steps);
    down += network::MaxRoundLettersInFlight(down_[i].params(), down_[i].timestep(), per_sample,
                                             period_steps);
  }
  up_in_flight_.SetCapacity(static_cast<size_t>(up));
  down_in_flight_.SetCapacity(static_cast<size_t>(down));
}

// Tagged with the sample index: in phase the same one-to-one key as the step; out of phase the
// solver gathers one index's R_i, taken up to clock_offset apart.
void CentralSolver::PostR(int follower, int64_t step, int64_t sample_index, const mjfMessage& r) {
  up_in_flight_.Post(up_[follower], follower, step, sample_index, r);
}

void CentralSolver::CollectAtSolver(int64_t step, double time) {
  arrived_.clear();
  up_in_flight_.Collect(step, up_, &arrived_);
  for (const network::RoundLetter& letter : arrived_) TakeR(letter, step, time);
}

void CentralSolver::CollectSolutions(int64_t step, std::vector<network::RoundLetter>* out) {
  down_in_flight_.Collect(step, down_, out);
}

void CentralSolver::TakeR(const network::RoundLetter& letter, int64_t step, double time) {
  const int i = letter.link;  // the up-link index is the follower's
  if (letter.sample_step < sample_) {
    ++up_late_[i];
    return;
  }
  if (letter.sample_step > sample_) {
    // A newer sample begins: an older one still missing some R_i cannot be solved any more.
    if (count_ > 0) ++skipped_samples_;
    sample_ = letter.sample_step;
    std::fill(has_.begin(), has_.end(), 0);
    count_ = 0;
  }
  if (has_[i]) return;  // one R_i per sample and follower: cannot repeat
  has_[i] = 1;
  ++count_;
  rows_[2 * i] = letter.message.payload[2];
  rows_[2 * i + 1] = letter.message.payload[3];
  if (count_ < n_followers_) return;
  for (int f = 0; f < n_followers_; ++f) {
    rhs_(f, 0) = rows_[2 * f];
    rhs_(f, 1) = rows_[2 * f + 1];
  }
  SolveRightHandSide();
  ++solves_;
  count_ = 0;
  std::fill(has_.begin(), has_.end(), 0);
  for (int f = 0; f < n_followers_; ++f) {
    mjfMessage w{};
    w.sender = 0;
    w.round = 0;
    w.send_time = time;
    w.n_payload = 2;
    w.payload[0] = solved_[2 * f];
    w.payload[1] = solved_[2 * f + 1];
    down_in_flight_.Post(down_[f], f, step, sample_, w);
  }
}

}  // namespace mjf::runner
