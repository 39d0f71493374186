// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/linear_consensus.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {

void LinearConsensusParams::Validate() const {
  for (auto [value, key] : {std::pair<double, const char*>{kp, "kp"}, {kv, "kv"}}) {
    if (!(value > 0.0 && std::isfinite(value))) {
      std::ostringstream out;
      out << "attribute '" << key << "': " << key << " > 0 is required (got " << value << ")";
      throw std::invalid_argument(out.str());
    }
  }
}

LinearConsensus::LinearConsensus(const Graph& graph, const LinearConsensusParams& params)
    : graph_(WithSpanningTree(graph)),
      params_(Validated(params)),
      acceleration_(2 * graph_.num_followers(), 0.0),
      error_(4 * graph_.num_followers(), 0.0),
      unused_sliding_(2 * graph_.num_followers(), 0.0) {}

void LinearConsensus::Update(const FormationInput& input) {
  // e_i of eq. (16) is exactly the neighbour sum of the consensus law; K is irrelevant here.
  ComputeErrorAndSliding(graph_, SlidingGains{}, input.leader_pv, input.follower_pv,
                         input.shape_now, error_.data(), unused_sliding_.data());
  for (int i = 0; i < graph_.num_followers(); ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      acceleration_[2 * i + axis] = input.shape_now[6 * i + 4 + axis] -
                                    params_.kp * error_[4 * i + axis] -
                                    params_.kv * error_[4 * i + 2 + axis];
    }
  }
}

}  // namespace mjf::formation
