// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/network/link.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mjformation/time_steps.hpp"

namespace mjf::network {
namespace {

bool IsProbability(double p) { return p >= 0.0 && p <= 1.0; }

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("network link: " + what);
}

}  // namespace

uint64_t LinkSeed(uint64_t run_seed, uint64_t link_index) {
  // SplitMix64 (Steele, Lea, Flood 2014) applied twice: neighbouring indices give unrelated
  // mt19937_64 seeds.
  auto mix = [](uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(run_seed) ^ (link_index + 1));
}

int64_t MaxInFlight(const LinkParams& params, double timestep) {
  // A message sent at s arrives by s + D (D the delay at the jitter's upper end); after the
  // delivery of step k, those in flight were sent in (k - D, k], one per period.
  const int64_t longest = StepsAtOrAfter(params.latency + params.jitter, timestep);
  return longest / std::max<int64_t>(params.period_steps, 1) + 1;
}

Link::Link(const LinkParams& params, double timestep, uint64_t seed)
    : params_(params),
      timestep_(timestep),
      random_(seed),
      ideal_(params.loss_model == LossModel::kBernoulli && params.loss == 0.0 &&
             params.jitter == 0.0),
      fixed_delay_steps_(0) {
  Require(timestep > 0.0 && std::isfinite(timestep), "timestep must be > 0");
  Require(params.period_steps >= 1, "period_steps must be >= 1");
  Require(params.latency >= 0.0 && std::isfinite(params.latency), "latency must be >= 0");
  Require(params.jitter >= 0.0 && std::isfinite(params.jitter), "jitter must be >= 0");
  Require(IsProbability(params.loss), "loss must be in [0, 1]");
  Require(IsProbability(params.burst_enter) && IsProbability(params.burst_exit) &&
              IsProbability(params.burst_loss),
          "burst parameters must be probabilities");
  Require(params.range >= 0.0 && std::isfinite(params.range), "range must be >= 0");
  fixed_delay_steps_ = StepsAtOrAfter(params.latency, timestep);
}

bool Link::DrawLoss() {
  if (ideal_) return false;  // u < 0 never holds, and nothing else reads the stream
  const double u = random_.Uniform();
  if (params_.loss_model == LossModel::kBernoulli) return u < params_.loss;
  // Gilbert-Elliott: the channel state moves first (one transition per message), then the
  // message is lost with the state's loss probability. Two draws per message.
  bad_ = bad_ ? !(u < params_.burst_exit) : (u < params_.burst_enter);
  return random_.Bernoulli(bad_ ? params_.burst_loss : params_.loss);
}

std::optional<int64_t> Link::Transmit(int64_t send_step) {
  ++stats_.sent;
  if (DrawLoss()) {
    ++stats_.lost;
    return std::nullopt;
  }
  return ArrivalStep(send_step);
}

int64_t Link::ArrivalStep(int64_t send_step) {
  if (!(params_.jitter > 0.0)) return send_step + fixed_delay_steps_;
  return send_step +
         StepsAtOrAfter(params_.latency + params_.jitter * random_.Uniform(), timestep_);
}

bool Link::TransmitRound() {
  ++stats_.rounds_sent;
  if (DrawLoss()) {
    ++stats_.rounds_lost;
    return false;
  }
  return true;
}

std::optional<int64_t> Link::TransmitRoundDelayed(int64_t send_step) {
  ++stats_.rounds_sent;
  if (DrawLoss()) {
    ++stats_.rounds_lost;
    return std::nullopt;
  }
  return ArrivalStep(send_step);
}

void Link::RecordRoundDelivery(int64_t send_step, int64_t arrival_step) {
  ++stats_.rounds_delivered;
  const double latency = static_cast<double>(arrival_step - send_step) * timestep_;
  stats_.round_latency_sum += latency;
  stats_.round_latency_max = std::max(stats_.round_latency_max, latency);
}

void Link::RecordDelivery(int64_t send_step, int64_t arrival_step, bool stale) {
  ++stats_.delivered;
  if (stale) ++stats_.stale;
  const double latency = static_cast<double>(arrival_step - send_step) * timestep_;
  stats_.latency_sum += latency;
  stats_.latency_max = std::max(stats_.latency_max, latency);
}

}  // namespace mjf::network
