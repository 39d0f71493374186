// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/channel_summary.hpp"

#include <algorithm>
#include <string>

namespace mjf::runner {
namespace {

using Json = nlohmann::json;

// summary.json rounds_over_links.policy: when a round runs and what the follower flies meanwhile.
std::string PolicyText(RoundPolicy policy) {
  return std::string(
             "a round runs when the previous round of every in-neighbour (or W_i) has arrived, or "
             "on the timeout with u_j for what is missing; ") +
         (policy == RoundPolicy::kHold
              ? "the command of the last finished exchange is held until this one finishes; "
              : "each round's result is applied at once; ") +
         "the next sample drops the rounds still missing";
}

Json LinksSummary(const network::Network& network) {
  Json links = Json::array();
  for (int l = 0; l < network.n_links(); ++l) {
    const network::LinkStats& st = network.link(l).stats();
    const int64_t arrived = st.delivered;
    links.push_back({{"from", network.spec(l).from},
                     {"to", network.spec(l).to},
                     {"sent", st.sent},
                     {"delivered", st.delivered},
                     {"lost", st.lost},
                     {"stale_dropped", st.stale},
                     {"out_of_range", st.out_of_range},
                     {"latency_mean_s", arrived > 0 ? st.latency_sum / arrived : 0.0},
                     {"latency_max_s", st.latency_max},
                     {"round_messages_sent", st.rounds_sent},
                     {"round_messages_lost", st.rounds_lost}});
  }
  return links;
}

// Age of information per follower: of every message held, and at the samples the law takes.
Json AgeSummary(const AgentRouting& routing, Json* sample_age) {
  const network::Network& network = routing.network();
  Json age = Json::array();
  for (int v = 1; v <= routing.n_followers(); ++v) {
    age.push_back(
        {{"follower", v}, {"mean_s", network.age(v).mean()}, {"max_s", network.age(v).max}});
  }
  *sample_age = Json::array();
  for (int i = 0; i < routing.n_followers(); ++i) {
    const network::AgeStats& a = routing.sample_age(i);
    sample_age->push_back(
        {{"follower", i + 1}, {"samples", a.ticks}, {"mean_s", a.mean()}, {"max_s", a.max}});
  }
  return age;
}

Json EventsSummary(const network::Network& network) {
  Json events = Json::array();
  for (const auto& e : network.events()) {
    if (events.size() >= 1000) break;  // the count beside it is complete
    events.push_back({{"time_s", e.time}, {"from", e.from}, {"to", e.to}, {"up", e.up}});
  }
  return events;
}

// rounds_over_links' totals over the followers.
RoundsOverLinks::RoundStats Totals(const RoundsOverLinks& rounds, int n_followers) {
  RoundsOverLinks::RoundStats total;
  total.rounds_run.assign(static_cast<size_t>(rounds.n_rounds()), 0);
  for (int i = 0; i < n_followers; ++i) {
    const RoundsOverLinks::RoundStats& st = rounds.stats(i);
    total.samples += st.samples;
    total.complete += st.complete;
    total.timed_out += st.timed_out;
    total.incomplete += st.incomplete;
    total.completion_sum += st.completion_sum;
    total.completion_max = std::max(total.completion_max, st.completion_max);
    for (size_t k = 0; k < st.rounds_run.size(); ++k) total.rounds_run[k] += st.rounds_run[k];
  }
  return total;
}

Json RoundLinksSummary(const RoundsOverLinks& rounds, const network::Network& network) {
  Json links = Json::array();
  for (int l = 0; l < network.n_links(); ++l) {
    if (network.spec(l).from == 0) continue;  // rounds travel on follower links only
    const network::LinkStats& st = network.link(l).stats();
    links.push_back({{"from", network.spec(l).from},
                     {"to", network.spec(l).to},
                     {"round_messages_delivered", st.rounds_delivered},
                     {"round_latency_mean_s",
                      st.rounds_delivered > 0 ? st.round_latency_sum / st.rounds_delivered : 0.0},
                     {"round_latency_max_s", st.round_latency_max},
                     {"round_messages_late", rounds.late(l)},
                     {"round_messages_unmatched", rounds.unmatched(l)}});
  }
  return links;
}

}  // namespace

Json NetworkSummary(const ChannelParts& parts) {
  const NetworkConfig& config = parts.config;
  const network::Network& network = parts.routing.network();
  Json sample_age;
  const Json age = AgeSummary(parts.routing, &sample_age);
  Json summary = {
      {"execution", ToString(config.execution)},
      {"coupling", ToString(config.coupling)},
      {"rounds_per_step", parts.n_rounds},
      {"central_solve_skipped_samples", parts.central ? parts.central->skipped_samples() : 0},
      {"jacobi_spectral_radius", parts.jacobi_spectral_radius},
      {"links", LinksSummary(network)},
      {"age_of_information", age},
      {"topology_switches", network.events().size()},
      {"topology_events", EventsSummary(network)},
      {"time_without_spanning_tree_s", network.time_without_spanning_tree()},
      {"predict", ToString(config.predict)},
      // Instantaneous exchange rounds take no time (Jacobi: loss only; the central solve: at
      // once, over every follower): that central solve is the ideal reference, not a protocol.
      // Over the links they take their latency.
      {"exchange_rounds", ToString(config.rounds)},
      {"oracle", config.coupling == Coupling::kCentralSolve && !parts.rounds},
      {"age_of_information_at_samples", sample_age},
      {"clocks", ClocksSummary(parts.clocks, parts.routing.n_followers())}};
  if (parts.rounds)
    summary["rounds_over_links"] = RoundsSummary(*parts.rounds, network, parts.central);
  return summary;
}

Json ClocksSummary(const AgentClocks& clocks, int n_followers) {
  Json offsets = Json::array(), drifts = Json::array();
  for (int i = 0; i < n_followers; ++i) {
    offsets.push_back(clocks.offset(i));
    drifts.push_back(clocks.drift(i) * 1e6);
  }
  Json summary = {{"in_phase", !clocks.active()}, {"offset_s", offsets}, {"drift_ppm", drifts}};
  // Written only when set, so that runs without it keep their summary's bytes.
  if (clocks.synchronised()) summary["synchronised"] = true;
  return summary;
}

Json RoundsSummary(const RoundsOverLinks& rounds, const network::Network& network,
                   const CentralSolver* central) {
  const int n_followers = rounds.n_followers();
  Json followers = Json::array();
  int64_t in_progress = 0;
  for (int i = 0; i < n_followers; ++i) {
    const RoundsOverLinks::RoundStats& st = rounds.stats(i);
    const int64_t finished = st.complete + st.timed_out;
    const bool open = rounds.exchange(i).waiting;
    followers.push_back({{"follower", i + 1},
                         {"samples", st.samples},
                         {"complete", st.complete},
                         {"timed_out", st.timed_out},
                         {"incomplete", st.incomplete},
                         {"in_progress_at_end", open ? 1 : 0},
                         {"rounds_run", st.rounds_run},
                         {"completion_mean_s", finished > 0 ? st.completion_sum / finished : 0.0},
                         {"completion_max_s", st.completion_max}});
    in_progress += open ? 1 : 0;
  }
  const RoundsOverLinks::RoundStats total = Totals(rounds, n_followers);
  const int64_t finished = total.complete + total.timed_out;
  const NetworkConfig& config = rounds.config();
  return {{"round_timeout_s", config.round_timeout},
          {"round_policy", ToString(config.round_policy)},
          {"policy", PolicyText(config.round_policy)},
          {"samples", total.samples},
          {"complete", total.complete},
          {"timed_out", total.timed_out},
          {"incomplete", total.incomplete},
          {"in_progress_at_end", in_progress},
          {"rounds_run", total.rounds_run},
          {"completion_mean_s", finished > 0 ? total.completion_sum / finished : 0.0},
          {"completion_max_s", total.completion_max},
          {"followers", followers},
          {"links", RoundLinksSummary(rounds, network)},
          {"solver", central ? SolverStarSummary(*central) : Json(nullptr)}};
}

Json SolverStarSummary(const CentralSolver& central) {
  Json star = Json::array();
  auto one = [](const network::Link& link, int64_t late) {
    const network::LinkStats& st = link.stats();
    return Json{{"sent", st.rounds_sent},
                {"lost", st.rounds_lost},
                {"delivered", st.rounds_delivered},
                {"latency_mean_s",
                 st.rounds_delivered > 0 ? st.round_latency_sum / st.rounds_delivered : 0.0},
                {"latency_max_s", st.round_latency_max},
                {"late", late}};
  };
  for (int i = 0; i < central.n_followers(); ++i) {
    star.push_back({{"follower", i + 1},
                    {"up_r", one(central.up_link(i), central.up_late(i))},
                    {"down_w", one(central.down_link(i), central.down_late(i))}});
  }
  return {{"node", 0},
          {"what",
           "vehicle 0 (the leader) solves L_H W = R when it holds every R_i of one "
           "sample; R_i up and W_i down on a star of links with each follower's "
           "leader-link parameters"},
          {"solves", central.solves()},
          {"links", star}};
}

}  // namespace mjf::runner
