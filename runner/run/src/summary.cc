// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/run/summary.hpp"

#include <cmath>
#include <cstdio>

#include "mjformation/control/delay_margin.hpp"
#include "mjformation/record/engine_identity.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/sim/simulation.hpp"

#ifndef MJF_VERSION
#define MJF_VERSION "0.0.0"
#endif

namespace mjf::runner {
namespace {

using Json = nlohmann::ordered_json;

Json PluginJson(const PluginInstance& p) {
  Json a = Json::object();
  for (const auto& [k, v] : p.attributes()) a[k] = v;
  return Json{{"name", p.descriptor().name}, {"attributes", a}};
}

// A plugin's report() as a JSON object (key -> number, null when not finite).
Json ReportJson(const std::vector<std::pair<std::string, double>>& report) {
  Json out = Json::object();
  for (const auto& [k, v] : report) out[k] = JsonNumber(v);
  return out;
}

// What ran: experiment, versions, vehicles, plugins, shape.
void DescribeExperiment(const Simulation& sim, Json& s) {
  const ExperimentConfig& config = sim.config();
  s["seed"] = config.seed;
  s["config_sha256"] = Sha256Hex(ConfigEcho(config));
  s["versions"] = {{"mjformation", MJF_VERSION},
                   {"mujoco", RunningEngine().version},
                   {"mujoco_library_sha256", RunningEngine().library_sha256},
                   {"plugin_abi", MJF_ABI_VERSION}};
  s["n_followers"] = config.followers;
  s["vehicle_model"] = config.model;
  s["rotor_model"] = ToString(config.rotor_model);
  s["plugins"]["leader"] = PluginJson(sim.leader_plugin());
  s["plugins"]["formation"] = sim.formation_plugin()
                                  ? PluginJson(*sim.formation_plugin())
                                  : Json{{"name", config.formation.plugin}, {"per_follower", true}};
  s["plugins"]["attitude"] = PluginJson(sim.attitude_plugin(0));
  s["shape"] = {{"type", ToString(config.shape.type)},
                {"radius", config.shape.radius},
                {"omega", config.shape.omega}};
  AddRealismSummary(config, &s);  // "sensors" / "wind", only when switched on
}

// "network", with the predicted delay margin when the law reports its T and q (eq. (48)).
void AddNetworkSummary(const Simulation& sim, Json& s) {
  s["network"] = sim.channel()->Summary();
  // The margin is law (48)'s (T and q); other laws (e.g. consensus_linear) get none.
  const plugin::contract::Law& law = sim.contracts().law;
  if (law.HasDelayMargin()) {
    s["network"]["delay_margin"] =
        DelayMarginSummary(law.period, law.q, sim.channel()->coupling_radius());
  }
}

// The followers' estimation accuracy among the metrics too, so a sweep's tables carry
// it (mean and 95 % interval over seeds: the Monte Carlo NEES check); only with an estimator.
void AddEstimationMetrics(const Json& estimation, Json* metrics) {
  if (!metrics->is_object() || !estimation.contains("followers")) return;
  const Json& f = estimation["followers"];
  for (const char* key : {"position_rms_m", "velocity_rms_m_s", "position_rms_relative_to_leader_m",
                          "nees_mean", "nees_fraction_in_single_band"}) {
    if (f.contains(key)) (*metrics)[std::string("estimation_") + key] = f[key];
  }
}

}  // namespace

Json BuildSummary(const Simulation& sim, const RunResult& result, const Json& recorded) {
  const ExperimentConfig& config = sim.config();
  Json s;
  s["experiment"] = config.name;
  s["complete"] = result.complete;
  s["error"] = result.complete ? Json(nullptr) : Json(result.error);
  if (result.signal) s["interrupted_by_signal"] = result.signal;  // only on interrupted runs
  s["paper_experiment"] = config.paper_experiment;
  s["sim_time_s"] = result.sim_time_s;  // the simulated time reached
  s["duration_s"] = config.duration;
  s["timestep_s"] = config.timestep;
  s["steps"] = result.steps;
  DescribeExperiment(sim, s);
  s["metrics"] = recorded.contains("metrics") ? recorded["metrics"] : Json(nullptr);
  if (recorded.contains("estimation")) AddEstimationMetrics(recorded["estimation"], &s["metrics"]);
  s["plugin_report"] = ReportJson(sim.FormationReport());
  // The attitude plugin's report (e.g. the bandwidths a small vehicle flew with); only
  // for plugins that report, so other runs' summaries stay as they were.
  const auto attitude_report = sim.AttitudeReport();
  if (!attitude_report.empty()) s["attitude_report"] = ReportJson(attitude_report);
  // The setup's warnings (torque authority, docs/VEHICLES.md); only when there are any.
  if (!sim.warnings().empty()) s["warnings"] = sim.warnings();
  s["snapshots"] = recorded.contains("snapshots") ? recorded["snapshots"] : Json::array();
  if (sim.channel()) AddNetworkSummary(sim, s);  // per-agent execution only
  for (const auto& [k, v] : recorded.items()) {
    if (!s.contains(k)) s[k] = v;  // further recorders' keys, after the established ones
  }
  // Timing varies run to run; it is the only part of the run directory that does.
  const double wall = result.wall_time_s;
  s["timing"] = {{"wall_time_s", wall},
                 {"real_time_factor", wall > 0 ? result.sim_time_s / wall : 0.0},
                 {"steps_per_second", wall > 0 ? result.steps / wall : 0.0}};
  if (sim.threads() > 1) s["timing"]["threads"] = sim.threads();  // partitioned physics
  // The sensor stage with its estimator plugins (only with an estimator, so other
  // runs' timing keys stay as they were).
  if (const auto* e = sim.estimation()) {
    s["timing"]["estimator_wall_s"] = e->wall_seconds();  // both below
    s["timing"]["sensor_models_wall_s"] = e->sensor_model_seconds();
    s["timing"]["estimator_plugins_wall_s"] = e->estimator_seconds();
  }
  return s;
}

std::string Assumption1Text(const nlohmann::ordered_json& summary) {
  if (!summary.contains("leader_acceleration")) return "";
  const auto& a = summary["leader_acceleration"];
  if (!a.contains("assumption1_holds") || !a["assumption1_holds"].is_boolean() ||
      a["assumption1_holds"].get<bool>()) {
    return "";
  }
  auto number = [&](const char* key) {
    return a.contains(key) && a[key].is_number() ? a[key].get<double>() : std::nan("");
  };
  char text[512];
  std::snprintf(text, sizeof(text),
                "Assumption 1 does not hold: the leader's measured acceleration left the bounds "
                "[%g, %g] m/s^2 (%s) on %.3g %% of the steps, first at t = %.3f s, by up to %.3g "
                "m/s^2; Theorem 2's band is not guaranteed (summary.json leader_acceleration)",
                a["bounds"][0].get<double>(), a["bounds"][1].get<double>(),
                a["bounds_source"].is_string() ? a["bounds_source"].get<std::string>().c_str() : "",
                100 * number("fraction_outside"), number("first_violation_time_s"),
                number("max_excess"));
  return text;
}

}  // namespace mjf::runner
