// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The central solve of per-agent execution ([network] coupling = "central_solve",
// docs/NETWORK.md): L_H W = R over the R_i the followers publish in round 0 (payload[2..3]),
// W_i handed back to follower i in its last round.
//   - Instantaneous (the ideal reference): solved at once from the round-0 messages.
//   - Over the links: the solver is vehicle 0 (the leader); follower i's R_i goes up and W_i comes
//     down on a pair of links with its leader link's parameters (a star, not the graph). The
//     solver solves when it holds every R_i of one sample index.
// Pure: no MuJoCo.
#ifndef MJFORMATION_CONTROL_CENTRAL_SOLVER_HPP_
#define MJFORMATION_CONTROL_CENTRAL_SOLVER_HPP_

#include <mjformation/plugin.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mjformation/formation/laplacian_solver.hpp"
#include "mjformation/network/network.hpp"
#include "mjformation/network/round_courier.hpp"

namespace mjf::formation {
class Graph;
}  // namespace mjf::formation

namespace mjf::runner {

class CentralSolver {
 public:
  explicit CentralSolver(const formation::Graph& graph);

  int n_followers() const { return n_followers_; }
  // Samples some follower did not publish R_i in (no solution: the last inputs close the loop).
  int64_t skipped_samples() const { return skipped_samples_; }

  // Instantaneous: L_H W = R for the R_i in outgoing[i].payload[2..3] of every follower that
  // sampled (n_payload > 0); time (s) names the tick in the error when a follower that sampled
  // published no R_i. Between samples nothing happens.
  void SolvePublished(const std::vector<mjfMessage>& outgoing, double time);
  void ClearSolution() { have_solution_ = false; }
  // Follower's W_i (x, y) of this tick's instantaneous solve, or null.
  const double* solution(int follower) const {
    return have_solution_ ? &solved_[2 * static_cast<size_t>(follower)] : nullptr;
  }

  // Over the links: the star's links (after every graph link's random stream, so that the graph
  // keeps the streams an instantaneous run has). defaults: [network]'s link parameters.
  void SetUpStar(const network::Network& network, const network::LinkParams& defaults,
                 uint64_t seed);
  // Follower's R_i (payload[2..3] of r) of the sample with this index, posted up at `step`.
  void PostR(int follower, int64_t step, int64_t sample_index, const mjfMessage& r);
  // The R_i arriving at the solver by `step`; a full sample is solved and each W_i posted down
  // (sent at time, s).
  void CollectAtSolver(int64_t step, double time);
  // Appends the W_i arriving at the followers by `step` (letter.link: the follower, sample_step:
  // the sample index, payload[0..1]: W_i).
  void CollectSolutions(int64_t step, std::vector<network::RoundLetter>* out);
  // A W_i that arrived for an exchange that no longer waits for it.
  void CountLateSolution(int follower) { ++down_late_[follower]; }

  int64_t solves() const { return solves_; }
  const network::Link& up_link(int follower) const { return up_[follower]; }
  const network::Link& down_link(int follower) const { return down_[follower]; }
  int64_t up_late(int follower) const { return up_late_[follower]; }
  // The star's couriers hold at most `per_sample` letters a sample each way per follower, the
  // sample period being `period_steps` (MaxRoundLettersInFlight): the fixed-length state's
  // bound. After SetUpStar.
  void SetStarCapacity(int64_t per_sample, int64_t period_steps);
  // The solve's state (a fixed-length archive): the instantaneous solve's, then, with a star over
  // the links, its links' streams and counts, the R_i and W_i in flight, the sample being
  // gathered and what of it has arrived.
  template <typename Archive>
  void VisitState(Archive& archive) {
    archive(solved_, have_solution_, skipped_samples_, solves_);
    if (up_.empty()) return;
    for (network::Link& link : up_) link.VisitState(archive);
    for (network::Link& link : down_) link.VisitState(archive);
    up_in_flight_.VisitState(archive);
    down_in_flight_.VisitState(archive);
    archive(sample_, has_, rows_, count_, up_late_, down_late_);
  }
  int64_t down_late(int follower) const { return down_late_[follower]; }

 private:
  void TakeR(const network::RoundLetter& letter, int64_t step, double time);
  void SolveRightHandSide();  // rhs_ -> solved_

  int n_followers_;
  formation::LaplacianSolver solver_;  // the factor of L_H
  Eigen::Matrix<double, Eigen::Dynamic, 2> rhs_;
  std::vector<double> solved_;  // [2 follower + axis]
  bool have_solution_ = false;
  int64_t skipped_samples_ = 0;
  // The star.
  std::vector<network::Link> up_, down_;  // [follower]
  network::RoundCourier up_in_flight_, down_in_flight_;
  std::vector<network::RoundLetter> arrived_;
  int64_t sample_ = -1;       // the sample whose R_i the solver is gathering
  std::vector<char> has_;     // [follower] R_i of sample_ arrived
  std::vector<double> rows_;  // [2 follower + axis] R_i as it arrived
  int count_ = 0;
  int64_t solves_ = 0;
  std::vector<int64_t> up_late_, down_late_;  // [follower]
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_CENTRAL_SOLVER_HPP_
