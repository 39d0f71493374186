// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <nlohmann/json.hpp>

#include "mjformation/config/experiment.hpp"
#include "mjformation/run/summary.hpp"

namespace mjf::runner {

void AddRealismSummary(const ExperimentConfig& c, nlohmann::ordered_json* summary) {
  if (c.sensors.enabled()) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::object();
    for (int k = 0; k < realism::kChannels; ++k) {
      const realism::ChannelNoise& n = c.sensors.params.channel[k];
      channels[realism::ChannelName(static_cast<realism::Channel>(k))] = {
          {"std", n.white_std},
          {"bias_walk", n.bias_walk},
          {"rate_hz", n.rate_hz},
          {"latency_s", n.latency_s}};
      // The wander keys only when used, so configurations without them keep their summary bytes.
      if (n.wander_sigma > 0) {
        auto& ch = channels[realism::ChannelName(static_cast<realism::Channel>(k))];
        ch["wander"] = n.wander_sigma;
        ch["wander_tau_s"] = n.wander_tau;
        ch["correlation"] = n.correlation;
      }
    }
    (*summary)["sensors"] = {
        {"preset", c.sensors.preset}, {"scale", c.sensors.scale}, {"channels", channels}};
    const realism::AccelNoise& a = c.sensors.params.accel;
    if (a.enabled) {
      (*summary)["sensors"]["accelerometer"] = {{"noise_density", a.noise_density},
                                                {"bias_walk", a.bias_walk}};
    }
  }
  if (c.wind.enabled()) {
    const realism::WindParams& p = c.wind.params;
    nlohmann::ordered_json wind = {{"mean", p.mean}, {"turbulence", c.wind.turbulence}};
    if (p.turbulence) {
      wind["w20"] = c.wind.w20;
      wind["sigma"] = p.dryden.sigma;
      wind["scale_length"] = p.dryden.scale_length;
      wind["airspeed"] = p.dryden.airspeed;
      wind["turbulence_rate_hz"] = p.turbulence_rate_hz;
      wind["turbulence_correlation"] = p.turbulence_correlation;
    }
    nlohmann::ordered_json gusts = nlohmann::ordered_json::array();
    for (const auto& g : p.gusts) {
      gusts.push_back({{"start", g.start}, {"duration", g.duration}, {"amplitude", g.amplitude}});
    }
    wind["gusts"] = gusts;
    wind["drag"] = {{"rotor_linear", c.wind.drag.rotor_linear},
                    {"cda_horizontal", c.wind.drag.cda_horizontal},
                    {"cda_vertical", c.wind.drag.cda_vertical},
                    {"air_density", c.wind.drag.air_density}};
    (*summary)["wind"] = wind;
  }
}

}  // namespace mjf::runner
