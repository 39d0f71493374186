// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The experiment file's key reference (key_reference.hpp). The words of a word key are the
// parser's EnumWord tables, the defaults the values of the structs it fills (ExperimentConfig,
// LinkParams, SensorParams::Ideal, DragParams::Iris): what is written here is what the parser
// does. What a key does is written once, here.
#include "mjformation/config/key_reference.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "mjformation/config/config.hpp"
#include "section_reader.hpp"

namespace mjf::runner {
namespace {

using Keys = std::vector<KeyEntry>;

// "\"a\", \"b\"": the words of an EnumWord table, in its order.
template <typename E, size_t N>
std::string Words(const EnumWord<E> (&words)[N]) {
  std::string out;
  for (const auto& [word, value] : words)
    out += (out.empty() ? "\"" : ", \"") + std::string(word) + "\"";
  return out;
}

// The word of `value` as a TOML string.
template <typename E, size_t N>
std::string WordOf(const EnumWord<E> (&words)[N], E value) {
  for (const auto& [word, v] : words) {
    if (v == value) return "\"" + std::string(word) + "\"";
  }
  return "";
}

std::string Number(double v) { return fmt::format("{}", v); }
std::string Bool(bool v) { return v ? "true" : "false"; }
template <size_t N>
std::string Vector(const std::array<double, N>& v) {
  return fmt::format("[{}]", fmt::join(v, ", "));
}

void AddRun(Keys& k) {
  const ExperimentConfig d;
  std::string events;
  for (const char* e : kSafetyEventKinds)
    events += (events.empty() ? "\"" : ", \"") + std::string(e) + "\"";
  k.insert(
      k.end(),
      {
          {"run", "name", "string", "", "", "the file's stem", "a plain folder name",
           "The run's name; runs go into runs/<name>.", ""},
          {"run", "duration", "number", "s", Number(d.duration), "", "> 0", "Simulated time.", ""},
          {"run", "timestep", "number", "s", Number(d.timestep), "", "(0, 0.01]",
           "MuJoCo's physics step.", ""},
          {"run", "seed", "integer", "", std::to_string(d.seed), "", ">= 0",
           "Seed of every random source (start jitter, sensor noise, wind, network, seeded "
           "plugins).",
           ""},
          {"run", "record_rate", "number", "Hz", Number(d.record_rate), "", "(0, 1/timestep]",
           "Rows per second of timeseries.csv.", ""},
          {"run", "metric_window", "[start, end]", "s", "", "the last 37.5 % of the run",
           "start < end, inside [0, duration]",
           "Window over which summary.json averages sigma_f (Table 1's [25, 40] s).", ""},
          {"run", "paper_experiment", "integer", "", std::to_string(d.paper_experiment), "",
           "0, 1, 2, 3",
           "Which of the paper's experiments the run reproduces (0: none); the report sets it "
           "beside the paper's numbers.",
           ""},
          {"run", "reaching_band", "number", "as s_i", Number(d.reaching_band), "", ">= 0",
           "|s| band of the reaching time in summary.json; 0: the formation plugin's delta.", ""},
          {"run", "record_leader_acceleration", "boolean", "", Bool(d.record_leader_acceleration),
           "", "",
           "Adds the leader's measured acceleration (leader_ax, leader_ay) to timeseries.csv.", ""},
          {"run", "stop_on", "[word, ...]", "", "[]", "", events,
           "Safety events that end the run (exit 3); every event is reported either way.", ""},
          {"run", "threads", "integer", "", std::to_string(d.threads), "",
           fmt::format("[1, {}]", kMaxThreads),
           "Physics partitions stepped in parallel, in lockstep; the results are the same.", ""},
          {"run", "plugin_path", "[string, ...]", "", "[]", "", "folders",
           "Extra folders searched for plugins, relative to the experiment file.", ""},
      });
}

void AddVehicles(Keys& k) {
  const ExperimentConfig d;
  k.insert(
      k.end(),
      {
          {"vehicles", "model", "string", "", "\"" + d.model + "\"", "",
           "\"quadrotor\", \"pointmass\" or an MJCF file",
           "The vehicle model (mjcf/, docs/VEHICLES.md); a path is relative to the experiment "
           "file.",
           ""},
          {"vehicles", "scene", "string", "", "\"scene\"", "", "a model name or an MJCF file",
           "The world around the vehicles (ground, light).", ""},
          {"vehicles", "followers", "integer", "", std::to_string(d.followers), "", "[1, 100000]",
           "Number of followers N (one leader besides).", ""},
          {"vehicles", "altitude", "number", "m", Number(d.altitude), "", "> 0",
           "Altitude setpoint of every vehicle (the protocols act in x-y).", ""},
          {"vehicles", "leader_start", "[x, y]", "m",
           fmt::format("[{}, {}]", d.leader_start[0], d.leader_start[1]), "", "",
           "The leader's start position.", ""},
          {"vehicles", "follower_start", "[[x, y], ...]", "m", "", "a small ring near the origin",
           "one per follower", "The followers' start positions.", ""},
          {"vehicles", "start_jitter", "number", "m", Number(d.start_jitter), "", ">= 0",
           "Seeded uniform perturbation of every start position.", ""},
          {"vehicles", "rotor_model", "word", "", WordOf(kRotorModelWords, d.rotor_model), "",
           Words(kRotorModelWords),
           "Rotor thrust through MuJoCo's actuators, or as the runner's applied wrench.", ""},
          {"vehicles", "contacts", "boolean", "", Bool(d.contacts), "", "",
           "Collision detection (false saves MuJoCo's broadphase at large N).", ""},
          {"vehicles", "fault", "[{...}, ...]", "", "[]", "none (every rotor healthy)",
           "[[vehicles.fault]] tables",
           "Actuator faults: from `at` on, the rotor gives (1 - thrust_share) x the thrust of its "
           "command clamped to its control range (both rotor models; not the point mass).",
           ""},
          {"vehicles.fault", "follower", "integer", "", "", "required", "1..followers",
           "The follower whose rotor fails.", ""},
          {"vehicles.fault", "rotor", "integer", "", "", "required",
           "0..rotors - 1 (the attitude plugin's actuator order)", "The rotor that fails.", ""},
          {"vehicles.fault", "at", "number", "s", "", "required", "[0, duration)",
           "Time from which the rotor is faulty.", ""},
          {"vehicles.fault", "thrust_share", "number", "", "", "required", "[0, 1]",
           "Share of the rotor's commanded thrust lost (1: the rotor stops).", ""},
          {"vehicles", "body", "string", "", "", "the model follows the vehicle contract",
           "a body of the model", "A foreign model's vehicle body (docs/VEHICLES.md).", ""},
          {"vehicles", "rotors", "[string, ...]", "", "", "the model follows the vehicle contract",
           "actuators of the model",
           "A foreign model's rotor actuators, in the attitude plugin's order.", ""},
          {"vehicles", "thrust", "string", "", "", "none (a rotor vehicle)",
           "an actuator of the model", "A thrust-and-moment vehicle's thrust actuator.",
           "moments = [\"mx\", \"my\", \"mz\"]"},
          {"vehicles", "moments", "[string, string, string]", "", "", "none (a rotor vehicle)",
           "3 actuators of the model",
           "A thrust-and-moment vehicle's moment actuators about body x, y, z.", "thrust = \"f\""},
      });
}

void AddTopology(Keys& k) {
  k.insert(k.end(),
           {
               {"topology", "leader_links", "[integer, ...]", "", "",
                "[1] without [topology]; required with it", "1..followers",
                "Followers that receive the leader's state (weight a_i0 = 1).", ""},
               {"topology", "leader_weights", "[number, ...]", "", "", "1 for leader_links, else 0",
                "one per follower", "The leader weights a_i0, overriding leader_links' 1.",
                "leader_links = [1]"},
               {"topology", "edges", "[[from, to(, weight)], ...]", "", "",
                "the chain 1 -> 2 -> ... -> N without [topology]", "1..followers",
                "Follower links: `to` receives `from`'s state, with weight a_ij (default 1).",
                "leader_links = [1]"},
               {"topology", "generate", "word", "", "", "none (edges as given)",
                Words(kTopologyGeneratorWords),
                "A generated follower graph for large N: the chain 1 -> ... -> N, or the ring "
                "(chain and N -> 1).",
                "leader_links = [1]"},
               {"topology", "switch", "[{...}, ...]", "", "[]", "none (one graph for the run)",
                "[[topology.switch]] tables",
                "Switching topologies: from each switch's `at` on, the swarm's formation law "
                "sees that switch's graph (a new instance of the law, created at load with the "
                "new graph, takes over the old one's declared state; central execution only).",
                "leader_links = [1]"},
               {"topology.switch", "at", "number", "s", "", "required",
                "inside the run, increasing", "Time from which this graph holds.", ""},
               {"topology.switch", "leader_links", "[integer, ...]", "", "", "required",
                "1..followers", "Followers that receive the leader's state from `at` on.", ""},
               {"topology.switch", "leader_weights", "[number, ...]", "", "",
                "1 for leader_links, else 0", "one per follower",
                "The leader weights a_i0 from `at` on, overriding leader_links' 1.", ""},
               {"topology.switch", "edges", "[[from, to(, weight)], ...]", "", "", "none",
                "1..followers; with leader_links a directed spanning tree rooted at the leader",
                "Follower links from `at` on (as [topology] edges).", ""},
           });
}

// "a guidance", "an attitude": the article a family name takes.
std::string WithArticle(const std::string& word) {
  const bool vowel = !word.empty() && std::string("aeiou").find(word[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + word;
}

// A plugin section's own key; every other key of it is an attribute of the chosen plugin.
KeyEntry PluginKey(const char* section, const std::string& fallback, const char* family) {
  return {section,
          "plugin",
          "string",
          "",
          fallback.empty() ? "" : "\"" + fallback + "\"",
          fallback.empty() ? "required" : "",
          WithArticle(family) + " plugin",
          std::string("The ") + family +
              " plugin; the section's other keys are its attributes (`mjformation plugins` lists "
              "them with defaults).",
          ""};
}

void AddShape(Keys& k) {
  const ShapeConfig d;
  k.insert(k.end(),
           {
               {"formation", "shape", "table", "", "", "none: f_i = 0", "[formation.shape]",
                "The desired formation f_i(t) (Definition 1).", ""},
               {"formation.shape", "type", "word", "", WordOf(kShapeTypeWords, d.type), "",
                Words(kShapeTypeWords),
                "The paper's rotating circle, fixed offsets, a sampled table, or none.", ""},
               {"formation.shape", "radius", "number", "m", Number(d.radius), "", "> 0",
                "Circle radius.", ""},
               {"formation.shape", "omega", "number", "rad/s", Number(d.omega), "", "",
                "Circle angular rate.", ""},
               {"formation.shape", "phase0", "number", "rad", Number(d.phase0), "", "",
                "Phase of follower 1 on the circle.", ""},
               {"formation.shape", "phase_step", "number", "rad", "", "2 pi / N", "< 0: 2 pi / N",
                "Phase between consecutive followers.", ""},
               {"formation.shape", "tolerance", "number", "m/s", Number(d.tolerance), "", "> 0",
                "Allowed mismatch between f_ip' and f_iv (Algorithms 1-2).", ""},
               {"formation.shape", "offsets", "[[x, y], ...]", "m", "", "none", "one per follower",
                "Fixed offsets (type = \"offsets\").", ""},
               {"formation.shape", "file", "string", "", "", "none", "a CSV file",
                "Sampled shape (type = \"table\"): rows t, then px, py, vx, vy per follower; "
                "relative to the experiment file.",
                ""},
           });
}

void AddRender(Keys& k) {
  const RenderConfig d;
  k.insert(
      k.end(),
      {
          {"render", "snapshots", "[number, ...]", "s", "[]", "", "[0, duration]",
           "Times of the PNG snapshots.", ""},
          {"render", "width", "integer", "px", std::to_string(d.width), "", "[16, 4096]",
           "Snapshot width.", ""},
          {"render", "height", "integer", "px", std::to_string(d.height), "", "[16, 4096]",
           "Snapshot height.", ""},
          {"render", "camera", "word", "", WordOf(kCameraModeWords, d.camera), "",
           Words(kCameraModeWords),
           "Camera target: the formation's centroid, the leader, or lookat.", ""},
          {"render", "distance", "number", "m", Number(d.distance), "", "", "Camera distance.", ""},
          {"render", "azimuth", "number", "deg", Number(d.azimuth), "", "", "Camera azimuth.", ""},
          {"render", "elevation", "number", "deg", Number(d.elevation), "", "", "Camera elevation.",
           ""},
          {"render", "lookat", "[x, y, z]", "m", Vector(d.lookat), "", "",
           "Camera target of camera = \"fixed\".", ""},
          {"render", "shadows", "boolean", "", Bool(d.shadows), "", "", "Shadows in snapshots.",
           ""},
          {"render", "trail_seconds", "number", "s", Number(d.trail_seconds), "", ">= 0",
           "Path drawn behind each vehicle.", ""},
          {"render", "video", "boolean", "", Bool(d.video), "", "", "Write video.mp4 (ffmpeg).",
           ""},
          {"render", "video_fps", "number", "Hz", Number(d.video_fps), "", "(0, 120]",
           "Video frame rate.", ""},
          {"render", "video_shadows", "boolean", "", Bool(d.video_shadows), "", "",
           "Shadows in the video (twice the cost of a frame).", ""},
          {"render", "video_width", "integer", "px", std::to_string(d.video_width), "",
           "even, [16, 4096]", "Video width.", ""},
          {"render", "video_height", "integer", "px", std::to_string(d.video_height), "",
           "even, [16, 4096]", "Video height.", ""},
      });
}

// The seven keys of each measured channel: <channel>_std, _bias_walk, ...
void AddSensorChannels(Keys& k) {
  const realism::SensorParams ideal = realism::SensorParams::Ideal();
  static const char* const kUnits[realism::kChannels] = {"m", "m/s", "rad", "rad/s"};
  for (int c = 0; c < realism::kChannels; ++c) {
    const std::string name = realism::ChannelName(static_cast<realism::Channel>(c));
    const std::string unit = kUnits[c];
    const realism::ChannelNoise& n = ideal.channel[c];
    const std::string of = " of the " + name + " measurement";
    k.insert(
        k.end(),
        {
            {"sensors", name + "_std", "number", unit, Number(n.white_std), "", ">= 0",
             "White noise standard deviation per axis" + of + " (overrides the preset).", ""},
            {"sensors", name + "_bias_walk", "number", unit + "/sqrt(s)", Number(n.bias_walk), "",
             ">= 0", "Random-walk intensity of the bias" + of + ".", ""},
            {"sensors", name + "_rate", "number", "Hz", Number(n.rate_hz), "",
             "0 or 1/rate a whole number of steps",
             "Samples per second" + of + ", held in between; 0: every physics step.", ""},
            {"sensors", name + "_latency", "number", "s", Number(n.latency_s), "",
             "whole steps, <= min(10, duration)", "Age of the truth a sample" + of + " reports.",
             ""},
            {"sensors", name + "_wander", "number", unit, Number(n.wander_sigma), "", ">= 0",
             "Stationary standard deviation of the GNSS-like Gauss-Markov wander" + of + ".", ""},
            {"sensors", name + "_wander_tau", "number", "s", Number(n.wander_tau), "", "> 0",
             "Correlation time of the wander" + of + ".", ""},
            {"sensors", name + "_correlation", "number", "", Number(n.correlation), "", "[0, 1]",
             "Fraction of the wander's variance shared by every vehicle" + of + ".", ""},
        });
  }
}

void AddSensors(Keys& k) {
  const SensorsConfig d;
  k.insert(
      k.end(),
      {
          {"sensors", "preset", "word", "", "\"" + d.preset + "\"", "", Words(kSensorPresetWords),
           "A named sensor suite (docs/REALISM.md); \"ideal\" is the truth, bit for bit.", ""},
          {"sensors", "scale", "number", "", Number(d.scale), "", "[0, 100]",
           "Multiplies the preset's white noise, bias walk and wander.", ""},
          {"sensors", "imu", "string", "", "", "the preset's", "\"icm42688\", \"ekf2\"",
           "The accelerometer's IMU grade.", ""},
      });
  AddSensorChannels(k);
  const realism::AccelNoise a = realism::SensorParams::Ideal().accel;
  k.insert(
      k.end(),
      {
          {"sensors", "accel_noise", "number", "m/s^2/sqrt(Hz)", Number(a.noise_density), "",
           ">= 0 (bounded)", "Accelerometer noise density (switches the accelerometer on).", ""},
          {"sensors", "accel_bias_walk", "number", "m/s^3/sqrt(Hz)", Number(a.bias_walk), "",
           ">= 0 (bounded)", "Accelerometer bias random walk (switches the accelerometer on).", ""},
      });
}

void AddWind(Keys& k) {
  const WindConfig d;
  k.insert(
      k.end(),
      {
          {"wind", "mean", "[x, y, z]", "m/s", Vector(d.params.mean), "", "components within +-50",
           "Mean wind, world frame.", ""},
          {"wind", "turbulence", "word", "", "\"" + d.turbulence + "\"", "",
           "\"none\", \"light\", \"moderate\", \"severe\", \"w20\"",
           "Dryden turbulence at a MIL-F-8785C intensity (15, 30, 45 kn at 20 ft), or at w20.", ""},
          {"wind", "w20", "number", "m/s", "", "none", "[0, 40]",
           "Wind speed at 20 ft setting the Dryden intensities.", "turbulence = \"w20\""},
          {"wind", "altitude", "number", "m", "", "[vehicles] altitude", "[0, 1000]",
           "Altitude of the Dryden parameters.", ""},
          {"wind", "airspeed", "number", "m/s", "", "max(1, horizontal mean wind)", "[0.5, 100]",
           "Speed carrying the frozen turbulence past a vehicle.", ""},
          {"wind", "turbulence_rate", "number", "Hz", Number(d.params.turbulence_rate_hz), "",
           "1/rate a whole number of steps", "Turbulence samples per second, held in between.", ""},
          {"wind", "turbulence_correlation", "number", "", Number(d.params.turbulence_correlation),
           "", "[0, 1]", "Correlation of the turbulence between any two vehicles.", ""},
          {"wind", "sigma", "[x, y, z]", "m/s", "", "the standard's", "[0, 20]",
           "Dryden intensities, overriding MIL-F-8785C's.", "turbulence = \"light\""},
          {"wind", "scale_length", "[x, y, z]", "m", "", "the standard's", "[1, 3000]",
           "Dryden scale lengths, overriding MIL-F-8785C's.", "turbulence = \"light\""},
          {"wind", "gusts", "[{...}, ...]", "", "[]", "", "[wind.gusts] tables", "1-cosine gusts.",
           ""},
          {"wind", "drag_rotor_linear", "number", "N s/m", Number(d.drag.rotor_linear), "", ">= 0",
           "Horizontal rotor drag coefficient (the Iris-like quadrotor's by default).", ""},
          {"wind", "drag_cda_horizontal", "number", "m^2", Number(d.drag.cda_horizontal), "",
           ">= 0", "Drag coefficient x frontal area.", ""},
          {"wind", "drag_cda_vertical", "number", "m^2", Number(d.drag.cda_vertical), "", ">= 0",
           "Drag coefficient x top area.", ""},
          {"wind", "air_density", "number", "kg/m^3", Number(d.drag.air_density), "", "(0, 2)",
           "Air density.", ""},
          {"wind.gusts", "start", "number", "s", "", "required", "inside the run",
           "Start of the gust.", ""},
          {"wind.gusts", "duration", "number", "s", "", "required",
           ">= 2 timesteps, ends inside the run", "Length of the gust.", ""},
          {"wind.gusts", "amplitude", "[x, y, z]", "m/s", "", "required", "components within +-50",
           "Peak gust velocity.", ""},
      });
}

void AddExecution(Keys& k) {
  const NetworkConfig d;
  k.insert(
      k.end(),
      {
          {"execution", "mode", "word", "", WordOf(kExecutionWords, d.execution), "",
           Words(kExecutionWords),
           "One swarm-level instance of the formation law, or one per follower over [network].",
           ""},
          {"execution", "coupling", "word", "", WordOf(kCouplingWords, d.coupling), "",
           Words(kCouplingWords),
           "How a per-agent follower closes its u_j(k) loop (docs/NETWORK.md).",
           "mode = \"per_agent\""},
          {"execution", "jacobi_rounds", "integer", "", std::to_string(d.jacobi_rounds), "",
           "[1, 64]", "Jacobi exchange rounds per sample.",
           "mode = \"per_agent\"\ncoupling = \"jacobi\""},
          {"execution", "jacobi_divergence", "word", "",
           WordOf(kJacobiDivergenceWords, d.refuse_divergent), "", Words(kJacobiDivergenceWords),
           "A Jacobi iteration that cannot converge is refused, or warned of.", ""},
          {"execution", "predict", "word", "", WordOf(kPredictWords, d.predict), "",
           Words(kPredictWords), "How a receiver carries a message up to its own sample time.",
           "mode = \"per_agent\""},
          {"execution", "clock_offset", "number", "s", Number(d.clock_offset), "",
           "[0, T), T the sample period", "Largest follower clock offset (each draws its own).",
           ""},
          {"execution", "clock_drift_ppm", "number", "ppm", Number(d.clock_drift_ppm), "",
           "[0, 1e4]", "Largest follower clock drift (each draws its own in [-value, value]).", ""},
          {"execution", "clock_sync", "boolean", "", Bool(d.clock_sync), "", "",
           "Followers' clocks synchronised to the leader's (GNSS time, PTP).", ""},
      });
}

// The link keys, shared by [network] (every link) and [[network.link]] (one link).
void AddLinkKeys(Keys& k, const std::string& section, const std::string& on) {
  const network::LinkParams d;
  const std::string base = section == "network" ? "" : "[network]'s";
  auto fallback = [&](const std::string& value) { return base.empty() ? value : ""; };
  auto text = [&](const std::string& value) { return base.empty() ? value : base; };
  k.insert(
      k.end(),
      {
          {section, "rate", "number", "Hz", "", text("every physics step"),
           "1/(n timestep), n >= 1", "Broadcast rate" + on + ".", ""},
          {section, "latency", "number", "s", fallback(Number(d.latency)), text(""),
           "whole steps, [0, duration]", "Fixed part of a message's delay" + on + ".", ""},
          {section, "jitter", "number", "s", fallback(Number(d.jitter)), text(""), "[0, duration]",
           "Uniform [0, jitter] added to each message's delay" + on + ".", ""},
          {section, "loss", "number", "", fallback(Number(d.loss)), text(""), "[0, 1]",
           "Loss probability" + on + " (Gilbert-Elliott: in the good state).", ""},
          {section, "loss_model", "word", "", fallback(WordOf(kLossModelWords, d.loss_model)),
           text(""), Words(kLossModelWords),
           "Independent losses, or Gilbert-Elliott bursts" + on + ".", ""},
          {section, "burst_enter", "number", "", fallback(Number(d.burst_enter)), text(""),
           "[0, 1]", "Gilbert-Elliott P(good -> bad) per message" + on + ".", ""},
          {section, "burst_exit", "number", "", fallback(Number(d.burst_exit)), text(""),
           "[0, 1], > 0 with bursts", "Gilbert-Elliott P(bad -> good) per message" + on + ".", ""},
          {section, "burst_loss", "number", "", fallback(Number(d.burst_loss)), text(""), "[0, 1]",
           "Gilbert-Elliott loss probability in the bad state" + on + ".", ""},
          {section, "range", "number", "m", "", text("no limit"), "> 0",
           "The link exists only while the vehicles are within it" + on + ".", ""},
      });
}

void AddNetwork(Keys& k) {
  const NetworkConfig d;
  AddLinkKeys(k, "network", " on every link");
  k.insert(k.end(),
           {
               {"network", "link", "[[network.link]]", "", "", "none", "links of the graph",
                "Per-link overrides of the keys above.", ""},
               {"network", "rounds", "word", "", WordOf(kExchangeRoundsWords, d.rounds), "",
                Words(kExchangeRoundsWords),
                "Exchange rounds inside a sample take no time, or travel over the links.", ""},
               {"network", "round_timeout", "number", "s", Number(d.round_timeout), "",
                "[0, duration]", "Longest wait for a round's messages (0: until the next sample).",
                "rounds = \"over_links\""},
               {"network", "round_policy", "word", "", WordOf(kRoundPolicyWords, d.round_policy),
                "", Words(kRoundPolicyWords),
                "What a follower flies while its exchange runs: each round's result, or its last "
                "finished command.",
                "rounds = \"over_links\""},
               {"network.link", "from", "integer", "", "", "required",
                "0 (the leader), 1..followers", "Sending vehicle.", ""},
               {"network.link", "to", "integer", "", "", "required", "1..followers",
                "Receiving follower.", ""},
           });
  AddLinkKeys(k, "network.link", " on this link");
}

void AddSafety(Keys& k) {
  const SafetyConfig d;
  k.insert(
      k.end(),
      {
          {"safety", "flip_tilt_deg", "number", "deg", Number(d.flip_tilt_deg), "", "(0, 180]",
           "Tilt of the body z axis from vertical beyond which a vehicle has flipped.", ""},
          {"safety", "near_miss_m", "number", "m", Number(d.near_miss_m), "", "[0, 1000]",
           "Gap between bounding spheres below which two vehicles nearly collide (0: off).", ""},
          {"safety", "region", "[[x0, x1], [y0, y1], [z0, z1]]", "m", "", "none", "min < max",
           "Leaving it is a left_region event.", ""},
      });
}

Keys BuildReference() {
  Keys k;
  AddRun(k);
  AddVehicles(k);
  AddTopology(k);
  k.push_back(PluginKey("leader", kDefaultLeaderPlugin, "guidance"));
  k.push_back(PluginKey("formation", "", "formation"));
  AddShape(k);
  k.push_back(PluginKey("attitude", kDefaultAttitudePlugin, "attitude"));
  AddRender(k);
  AddSensors(k);
  AddWind(k);
  AddExecution(k);
  AddNetwork(k);
  k.push_back(PluginKey("estimator", kDefaultEstimatorPlugin, "estimator"));
  AddSafety(k);
  return k;
}

// "`40`", or the phrase.
std::string DefaultCell(const KeyEntry& e) {
  return e.default_toml.empty() ? e.default_text : "`" + e.default_toml + "`";
}

std::string Escape(std::string text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string SectionTable(const std::string& section, const Keys& keys) {
  const bool array =
      section == "network.link" || section == "topology.switch" || section == "vehicles.fault";
  std::string out = fmt::format("\n## {}{}{}\n\n", array ? "[[" : "[", section, array ? "]]" : "]");
  out += "| key | type | unit | default | range | what it does |\n|---|---|---|---|---|---|\n";
  for (const KeyEntry& e : keys) {
    if (e.section != section) continue;
    std::string what = e.what;
    if (!e.needs.empty()) {
      std::string needs = e.needs;
      for (size_t at; (at = needs.find('\n')) != std::string::npos;) needs.replace(at, 1, "`, `");
      what += " Needs `" + needs + "`.";
    }
    out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", e.key, Escape(e.type), e.unit,
                       Escape(DefaultCell(e)), Escape(e.range), Escape(what));
  }
  return out;
}

}  // namespace

const std::vector<KeyEntry>& ExperimentKeyReference() {
  static const Keys reference = BuildReference();
  return reference;
}

std::string KeyReferenceMarkdown(const std::string& section) {
  const Keys& keys = ExperimentKeyReference();
  std::vector<std::string> sections;  // in the reference's order, sub-tables after their section
  for (const KeyEntry& e : keys) {
    if (std::find(sections.begin(), sections.end(), e.section) == sections.end())
      sections.push_back(e.section);
  }
  const bool known =
      section.empty() || std::find(std::begin(kExperimentSections), std::end(kExperimentSections),
                                   section) != std::end(kExperimentSections);
  if (!known) {
    throw ConfigError("keys: unknown section '" + section +
                      "' (known: " + fmt::format("{}", fmt::join(kExperimentSections, ", ")) + ")");
  }
  std::string out;
  if (section.empty()) {
    out =
        "# The experiment file: every key\n\n"
        "Generated by `mjformation keys` from the parser's own tables "
        "(runner/config/src/key_reference.cc); do not edit: regenerate with\n"
        "`build/runner/mjformation keys > docs/EXPERIMENT_FILE.md`. A test fails when the parser "
        "accepts a key this page lacks, or when this page is stale.\n\n"
        "An experiment file is TOML; every key is optional unless its default says required. "
        "`--set section.key=value` overrides any key from the command line. In [leader], "
        "[formation], [attitude] and [estimator] every key besides those listed is an attribute "
        "of the chosen plugin: `mjformation plugins` lists each plugin's attributes with their "
        "defaults.\n";
  }
  for (const std::string& s : sections) {
    if (section.empty() || s == section || s.rfind(section + ".", 0) == 0)
      out += SectionTable(s, keys);
  }
  return out;
}

std::map<std::string, std::set<std::string>> AcceptedKeys(const std::string& text,
                                                          const std::string& path) {
  AcceptedKeyMap accepted;
  AcceptedKeysRecorder recorder(&accepted);
  ParseExperiment(text, path);
  return accepted;
}

}  // namespace mjf::runner
