// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/network/network.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mjf::network {
namespace {

// The round part (round, n_payload, payload) of a held message as a receiver sees it in round
// `round`: the neighbour's round message when one of that round got through (`sent`, nullptr:
// none this tick), else the held message's own.
void SetRoundPart(const mjfMessage& held, const mjfMessage* sent, int round, mjfMessage* m) {
  const bool fresh = sent && sent->round == round;
  const mjfMessage& source = fresh ? *sent : held;
  m->round = fresh ? round : held.round;
  m->n_payload = source.n_payload;
  std::copy(source.payload, source.payload + MJF_MESSAGE_PAYLOAD, m->payload);
}

}  // namespace

Network::Network(int n_followers, std::vector<LinkSpec> links, double timestep, uint64_t seed)
    : n_vehicles_(n_followers + 1),
      timestep_(timestep),
      specs_(std::move(links)),
      out_links_(n_vehicles_),
      in_links_(n_vehicles_),
      age_(n_vehicles_) {
  links_.reserve(specs_.size());
  for (size_t l = 0; l < specs_.size(); ++l) {
    const LinkSpec& s = specs_[l];
    if (s.from < 0 || s.from >= n_vehicles_ || s.to < 1 || s.to >= n_vehicles_ || s.from == s.to) {
      throw std::invalid_argument("network: link " + std::to_string(s.from) + " -> " +
                                  std::to_string(s.to) + " does not join two vehicles");
    }
    links_.emplace_back(s.params, timestep, LinkSeed(seed, l));
    capacity_.push_back(MaxInFlight(s.params, timestep));
    out_links_[s.from].push_back(static_cast<int>(l));
    in_links_[s.to].push_back(static_cast<int>(l));
  }
  up_.assign(specs_.size(), true);
  in_flight_.resize(specs_.size());
  held_.resize(specs_.size());
  has_held_.assign(specs_.size(), false);
  round_.resize(specs_.size());
  has_round_.assign(specs_.size(), false);
  spanning_ = SpanningTree();
}

// Breadth-first search from the leader over the links that exist now.
bool Network::SpanningTree() const {
  std::vector<bool> reached(n_vehicles_, false);
  std::vector<int> queue = {0};
  reached[0] = true;
  for (size_t q = 0; q < queue.size(); ++q) {
    for (int l : out_links_[queue[q]]) {
      const int to = specs_[l].to;
      if (up_[l] && !reached[to]) {
        reached[to] = true;
        queue.push_back(to);
      }
    }
  }
  return std::all_of(reached.begin(), reached.end(), [](bool r) { return r; });
}

void Network::UpdateTopology(int64_t step, const std::vector<std::array<double, 3>>& positions) {
  bool changed = false;
  for (size_t l = 0; l < specs_.size(); ++l) {
    const double range = specs_[l].params.range;
    if (range <= 0.0) continue;
    const auto& a = positions[specs_[l].from];
    const auto& b = positions[specs_[l].to];
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const bool up = dx * dx + dy * dy + dz * dz <= range * range;
    if (up != up_[l] || !topology_known_) {
      if (up != up_[l]) {
        events_.push_back(
            {static_cast<double>(step) * timestep_, specs_[l].from, specs_[l].to, up});
      }
      up_[l] = up;
      changed = true;
    }
  }
  topology_known_ = true;
  if (changed) spanning_ = SpanningTree();
  if (!spanning_) ++steps_without_tree_;
}

void Network::Broadcast(int64_t step, int sender, const mjfMessage& message) {
  for (int l : out_links_[sender]) {
    Link& link = links_[l];
    if (!link.Broadcasts(step)) continue;
    if (!up_[l]) {
      link.RecordOutOfRange();
      continue;
    }
    if (auto arrival = link.Transmit(step)) in_flight_[l].push_back({*arrival, step, message});
  }
}

void Network::Deliver(int64_t step) {
  for (size_t l = 0; l < specs_.size(); ++l) {
    auto& flight = in_flight_[l];
    size_t kept = 0;
    for (size_t m = 0; m < flight.size(); ++m) {
      if (flight[m].arrival_step > step) {
        if (kept != m) flight[kept] = flight[m];
        ++kept;
        continue;
      }
      // Newer message wins: one sent before the message held is dropped on arrival.
      const bool stale = has_held_[l] && flight[m].message.send_time < held_[l].send_time;
      links_[l].RecordDelivery(flight[m].send_step, step, stale);
      if (!stale) {
        held_[l] = flight[m].message;
        has_held_[l] = true;
      }
    }
    flight.resize(kept);
  }
  const double now = static_cast<double>(step) * timestep_;
  for (int v = 1; v < n_vehicles_; ++v) {
    double oldest = now;
    for (int l : in_links_[v]) oldest = std::min(oldest, has_held_[l] ? held_[l].send_time : 0.0);
    AgeStats& a = age_[v];
    const double age = now - oldest;
    a.sum += age;
    a.max = std::max(a.max, age);
    ++a.ticks;
  }
}

void Network::Inbox(int receiver, int round, std::vector<mjfMessage>* out,
                    const mjfMessage** leader) const {
  out->clear();
  *leader = nullptr;
  for (int l : in_links_[receiver]) {
    if (!has_held_[l]) continue;
    if (specs_[l].from == 0) {
      *leader = &held_[l];
      continue;
    }
    out->push_back(held_[l]);
    if (round >= 0)
      SetRoundPart(held_[l], has_round_[l] ? &round_[l] : nullptr, round, &out->back());
  }
}

void Network::RefreshRound(int receiver, int round, std::vector<mjfMessage>* out) const {
  size_t k = 0;
  for (int l : in_links_[receiver]) {
    if (!has_held_[l] || specs_[l].from == 0) continue;
    SetRoundPart(held_[l], has_round_[l] ? &round_[l] : nullptr, round, &(*out)[k++]);
  }
}

void Network::ExchangeRound(int sender, const mjfMessage& message) {
  for (int l : out_links_[sender]) {
    if (!up_[l] || specs_[l].from == 0) continue;
    if (links_[l].TransmitRound()) {
      round_[l] = message;
      has_round_[l] = true;
    }
  }
}

void Network::SendRound(int64_t step, int sender, int64_t sample_step, const mjfMessage& message) {
  for (int l : out_links_[sender]) {
    if (!up_[l] || specs_[l].from == 0) continue;
    rounds_in_flight_.Post(links_[l], l, step, sample_step, message);
  }
}

void Network::CollectRounds(int64_t step, std::vector<RoundLetter>* out) {
  rounds_in_flight_.Collect(step, links_, out);
}

void Network::ClearRounds() { std::fill(has_round_.begin(), has_round_.end(), false); }

}  // namespace mjf::network
