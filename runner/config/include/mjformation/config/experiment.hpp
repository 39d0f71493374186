// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The experiment as a typed struct: what the parser (config.hpp) fills and every stage reads.
// Plain data only: it includes the parameter structs of realism/ and network/, never their
// models, and nothing here parses. Plugin attributes are kept as strings and checked against
// the plugin's declaration by the plugin host.
#ifndef MJFORMATION_CONFIG_EXPERIMENT_HPP_
#define MJFORMATION_CONFIG_EXPERIMENT_HPP_

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mjformation/network/link_params.hpp"
#include "mjformation/realism/drag.hpp"
#include "mjformation/realism/sensor_params.hpp"
#include "mjformation/realism/wind_params.hpp"

namespace mjf::runner {

// The experiment's choices, parsed once into enums: no string is compared while a run steps.
// Each enum has one table of its words in the experiment file and summary.json, in the order
// refusals list them: the parser reads through it (SectionReader::Enum) and ToString writes
// through it, so a word is spelled in one place.
template <typename E>
using EnumWord = std::pair<const char*, E>;
enum class RotorModel { kActuator, kWrench };  // MuJoCo's actuators, or the runner's wrench
enum class CameraMode { kFollow, kLeader, kFixed };
enum class ShapeType { kCircle, kOffsets, kTable, kNone };
// Their names in the experiment file and in summary.json.
inline constexpr EnumWord<RotorModel> kRotorModelWords[] = {{"actuator", RotorModel::kActuator},
                                                            {"wrench", RotorModel::kWrench}};
inline constexpr EnumWord<CameraMode> kCameraModeWords[] = {{"follow", CameraMode::kFollow},
                                                            {"leader", CameraMode::kLeader},
                                                            {"fixed", CameraMode::kFixed}};
inline constexpr EnumWord<ShapeType> kShapeTypeWords[] = {{"circle", ShapeType::kCircle},
                                                          {"offsets", ShapeType::kOffsets},
                                                          {"table", ShapeType::kTable},
                                                          {"none", ShapeType::kNone}};
const char* ToString(RotorModel value);
const char* ToString(CameraMode value);
const char* ToString(ShapeType value);

// [execution] and [network] (runner/config/src/network_config.cc, docs/NETWORK.md): how the
// formation protocol runs (one swarm-level instance, or one instance per follower over a simulated
// network) and how the per-agent form closes its u_j(k) loop.
enum class Execution { kCentral, kPerAgent };
enum class Coupling { kLastInput, kJacobi, kCentralSolve };
inline constexpr EnumWord<Execution> kExecutionWords[] = {{"central", Execution::kCentral},
                                                          {"per_agent", Execution::kPerAgent}};
inline constexpr EnumWord<Coupling> kCouplingWords[] = {{"last_input", Coupling::kLastInput},
                                                        {"jacobi", Coupling::kJacobi},
                                                        {"central_solve", Coupling::kCentralSolve}};
const char* ToString(Execution value);
const char* ToString(Coupling value);
// [execution] predict: how a receiver carries a neighbour's or the leader's message
// from the time its state refers to up to its own sample time, before the law sees it.
// kNone: as received (the default); kInput: model (40) under zero-order hold with the sender's
// input u_j; kAttitude: with the horizontal acceleration implied by the sender's tilt at hover
// thrust (vehicles whose attitude loop lags the command).
enum class Predict { kNone, kInput, kAttitude };
inline constexpr EnumWord<Predict> kPredictWords[] = {
    {"none", Predict::kNone}, {"input", Predict::kInput}, {"attitude", Predict::kAttitude}};
const char* ToString(Predict value);
// [network] rounds: how the exchange rounds inside one sample (Jacobi iterates w_j,
// the central solve's R_i and W_i) travel. kInstantaneous: they take no time (loss only; the
// central solve at once: an oracle, the default); kOverLinks: over the links with their latency,
// jitter and loss, a round starting only when the previous one has arrived (docs/NETWORK.md).
enum class ExchangeRounds { kInstantaneous, kOverLinks };
inline constexpr EnumWord<ExchangeRounds> kExchangeRoundsWords[] = {
    {"instantaneous", ExchangeRounds::kInstantaneous}, {"over_links", ExchangeRounds::kOverLinks}};
const char* ToString(ExchangeRounds value);
// [network] round_policy (rounds = "over_links"): what a follower flies while its exchange runs.
// kApply: each round's result at once (from round 0's last-input estimate on); kHold: the
// command of its last finished exchange until this one finishes (an input delay instead of a
// wrong input; docs/NETWORK.md).
enum class RoundPolicy { kApply, kHold };
inline constexpr EnumWord<RoundPolicy> kRoundPolicyWords[] = {{"apply", RoundPolicy::kApply},
                                                              {"hold", RoundPolicy::kHold}};
const char* ToString(RoundPolicy value);
// [network] loss_model: independent losses, or Gilbert-Elliott bursts (docs/NETWORK.md).
inline constexpr EnumWord<network::LossModel> kLossModelWords[] = {
    {"bernoulli", network::LossModel::kBernoulli},
    {"gilbert_elliott", network::LossModel::kGilbertElliott}};
// [execution] jacobi_divergence: a Jacobi iteration that cannot converge is refused, or warned of.
inline constexpr EnumWord<bool> kJacobiDivergenceWords[] = {{"refuse", true}, {"warn", false}};
// [topology] generate, for large N: the chain 1 -> 2 -> ... -> N (false), or the ring (true:
// the chain and N -> 1).
inline constexpr EnumWord<bool> kTopologyGeneratorWords[] = {{"chain", false}, {"ring", true}};
// [sensors] preset: the named sensor suites (realism/sensor_params.hpp).
using SensorSuite = realism::SensorParams (*)();
inline constexpr EnumWord<SensorSuite> kSensorPresetWords[] = {
    {"ideal", &realism::SensorParams::Ideal},
    {"typical", &realism::SensorParams::Typical},
    {"consumer_gnss", &realism::SensorParams::ConsumerGnss},
    {"rtk", &realism::SensorParams::Rtk},
    {"mocap", &realism::SensorParams::MotionCapture}};

struct NetworkConfig {
  Execution execution = Execution::kCentral;
  Coupling coupling = Coupling::kLastInput;
  int jacobi_rounds = 1;         // exchange rounds per sample (coupling = "jacobi")
  bool refuse_divergent = true;  // jacobi_divergence = "refuse" (else "warn")
  network::LinkParams defaults;  // [network]: every link (ideal when the section is absent)
  struct LinkOverride {
    int from = 0;  // vehicle: 0 = leader, 1..N followers (the paper's numbering)
    int to = 1;
    int line = 0;
    network::LinkParams params;
  };
  std::vector<LinkOverride> links;  // [[network.link]]
  // [execution] timing keys (execution_timing_config.cc): receiver-side prediction, and the
  // followers' clocks: follower i's clock reads (1 + drift_i) t + offset_i, with offset_i drawn
  // uniformly in [0, clock_offset] and drift_i in [-clock_drift_ppm, clock_drift_ppm] 1e-6
  // (seeded by the run's seed). All zero: every follower samples in phase with the leader.
  Predict predict = Predict::kNone;
  double clock_offset = 0.0;     // s, the largest offset; < the sample period
  double clock_drift_ppm = 0.0;  // ppm, the largest |drift|; <= 1e4
  // [execution] clock_sync: true when the followers' clocks are synchronised to the leader's
  // (GNSS time, PTP): the offset and drift above then shift only when each follower's loop
  // samples, while its time stamps, its formation reference h_i(t) and its prediction read the
  // common time. false (default): each follower reads its own free-running clock for all of it.
  bool clock_sync = false;
  // [network] rounds, round_timeout: exchange rounds carried over the links.
  ExchangeRounds rounds = ExchangeRounds::kInstantaneous;
  // s, over_links: a follower waiting longer than this for a round's messages runs the next
  // round with what it has (0: no timeout, it waits until its next sample).
  double round_timeout = 0.0;
  RoundPolicy round_policy = RoundPolicy::kApply;
  // s, derived at parse time: the sample period T ([formation] period, else the timestep). The
  // central solve over links gathers the R_i of one sample index floor(c_i(t) / T).
  double sample_period = 0.0;
};

// One plugin attribute as written in the experiment file.
struct AttributeValue {
  std::string text;    // value converted to the ABI's string form ("3 1" for arrays)
  int line = 0;        // source line, for messages
  std::string origin;  // "--set section.key=value" when it came from the command line, else ""
};

// The plugin of a plugin section that does not name one ([formation] must).
inline constexpr const char* kDefaultLeaderPlugin = "circle";
inline constexpr const char* kDefaultAttitudePlugin = "pd_cascade";
inline constexpr const char* kDefaultEstimatorPlugin = "passthrough";

// A [leader] / [formation] / [attitude] section: plugin name plus its attributes.
// Where a value was given, for the messages that name it after parsing (docs/ARCHITECTURE.md,
// failure contract): a line of the experiment file, or the command-line argument that gave it
// ("--set run.threads=4", "--threads 8"); neither (line 0, no argument): a default.
struct ValueOrigin {
  int line = 0;
  std::string argument;
};

// The sections an experiment file may have, in the order the documentation lists them.
inline constexpr const char* kExperimentSections[] = {
    "run",     "vehicles", "topology",  "leader",  "formation", "attitude", "render",
    "sensors", "wind",     "execution", "network", "estimator", "safety"};

// Physics partitions at most ([run] threads, run and bench --threads).
constexpr int kMaxThreads = 1024;

struct PluginSection {
  std::string section;  // "leader", "formation", "attitude", "estimator"
  std::string plugin;
  int line = 0;  // line of the `plugin` key
  // "--set section={...}" when the plugin key (or, without one, the section) came from the
  // command line, else "": where refusals of the plugin point.
  std::string origin;
  std::map<std::string, AttributeValue> attributes;
  // Defaults the runner derives for attributes the file leaves out, used only when the plugin
  // declares the key: "seed" = [run] seed, so run.seed drives every seeded plugin unless the
  // file pins the plugin's own seed (docs/ARCHITECTURE.md, "Random sources").
  std::map<std::string, std::string> derived;
};

// [formation.shape]: the desired formation f_i(t) (Definition 1).
struct ShapeConfig {
  // "circle": the paper's rotating circle; "offsets": fixed offsets [[x, y], ...] (m);
  // "table": a CSV file of t, then px, py, vx, vy per follower (interpolated); "none".
  ShapeType type = ShapeType::kCircle;
  double radius = 10.0;                        // m
  double omega = 0.314;                        // rad/s
  double phase0 = 0.0;                         // rad, phase of follower 1
  double phase_step = -1.0;                    // rad between consecutive followers; < 0: 2 pi / N
  std::vector<std::array<double, 2>> offsets;  // "offsets"
  std::string file;                            // "table": resolved path
  double tolerance = 1e-3;  // m/s: allowed mismatch of f_ip' and f_iv (Algorithms 1-2)
};

struct RenderConfig {
  std::vector<double> snapshots;  // s; empty: none
  int width = 1280;
  int height = 720;
  CameraMode camera = CameraMode::kFollow;  // formation centroid, the leader, or fixed
  double distance = 45.0;                   // m
  double azimuth = 90.0;                    // deg
  double elevation = -55.0;                 // deg
  std::array<double, 3> lookat = {0, 0, 0};
  // Off by default: at the default 45 m a vehicle's shadow is a dark blob on the ground that
  // reads as another object (docs/ARCHITECTURE.md, run directory).
  bool shadows = false;
  double trail_seconds = 10.0;  // s of path drawn behind each vehicle
  bool video = false;
  double video_fps = 25.0;
  bool video_shadows = false;  // shadows double the cost of a frame (docs/PERFORMANCE.md)
  int video_width = 640;
  int video_height = 480;
};

// The actuation contract of the vehicle's actuators (mjfActuation of the plugin ABI).
enum class VehicleActuation { kRotors = 0, kThrustMoments = 1 };

// [safety] and [run] stop_on: what counts as a safety event (docs/ARCHITECTURE.md, "Safety
// events"). Events are found in every run and reported; only stop_on ends a run at one.
struct SafetyConfig {
  double flip_tilt_deg = 90.0;  // tilt of the body z axis from vertical beyond this: a flip
  double near_miss_m = 0.5;     // gap between two vehicles' bounding spheres below this: near miss
  bool has_region = false;      // [safety] region given: leaving it is an event
  std::array<double, 6> region = {0, 0, 0, 0, 0, 0};  // x min, max, y min, max, z min, max (m)
  std::vector<std::string> stop_on;                   // event kinds that end the run (exit 3)
};

// The kinds of safety event, as summary.json and [run] stop_on name them.
inline const char* const kSafetyEventKinds[] = {"flip", "ground_impact", "collision", "near_miss",
                                                "left_region"};

// [sensors]: what the controllers measure. Default "ideal": the truth, bit for bit.
struct SensorsConfig {
  std::string preset = "ideal";  // "ideal", "typical", "consumer_gnss", "rtk", "mocap"
  double scale = 1.0;            // multiplies the preset's white noise, bias walk and wander
  std::string imu;               // an IMU grade for the accelerometer ("icm42688", "ekf2")
  realism::SensorParams params;  // preset, scaled, then the per-channel keys applied
  bool enabled() const { return !params.IsIdeal(); }
};

// [wind]: mean wind, Dryden turbulence and 1-cosine gusts, acting through the drag model.
struct WindConfig {
  std::string turbulence = "none";  // "none", "light", "moderate", "severe" or "w20"
  double w20 = 0.0;                 // m/s, wind speed at 20 ft setting the Dryden intensities
  realism::WindParams params;
  realism::DragParams drag = realism::DragParams::Iris();
  bool enabled() const { return !params.IsCalm(); }
};

struct ExperimentConfig {
  std::string source_path;             // the TOML file
  std::string source_text;             // its bytes, echoed to the run directory and hashed
  std::vector<std::string> overrides;  // --set section.key=value, applied in order
  std::string effective_text;          // with overrides: the merged TOML (what ran); else empty

  // [run]
  std::string name;
  double duration = 40.0;   // s
  double timestep = 0.001;  // s, physics
  uint64_t seed = 1;
  double record_rate = 100.0;  // Hz
  // s, mean sigma_f window (Table 1); default the last 37.5 % of the run ([25, 40] for 40 s)
  std::array<double, 2> metric_window = {25.0, 40.0};
  int paper_experiment = 0;              // 1..3 when this reproduces one
  std::vector<std::string> plugin_path;  // extra plugin folders
  double reaching_band = 0.0;            // |s| band for the reaching time; 0: the plugin's "delta"
  // Adds leader_ax, leader_ay (measured, m/s^2) to timeseries.csv; off keeps the old columns.
  bool record_leader_acceleration = false;
  // Physics partitions, each stepped on its own thread in lockstep with the one control tick
  // (partitioned_physics.hpp); 1: the single whole-swarm model. Same results either way.
  int threads = 1;
  ValueOrigin threads_origin;  // the file's line, --set run.threads=K or --threads K

  SafetyConfig safety;  // [safety], [run] stop_on

  // [vehicles]
  std::string model = "quadrotor";  // "quadrotor", "pointmass" or a path to an MJCF file
  std::string model_path;           // resolved
  std::string scene_path;           // resolved mjcf/scene.xml (or [vehicles] scene)
  int followers = 6;
  double altitude = 5.0;  // m, every vehicle's altitude setpoint
  std::array<double, 2> leader_start = {20.0, 0.0};
  std::vector<std::array<double, 2>> follower_start;  // empty: a small ring near the origin
  double start_jitter = 0.0;                          // m, seeded uniform perturbation
  RotorModel rotor_model = RotorModel::kActuator;
  // false: no collision detection at all. Vehicles never touch each other anyway (see
  // mjcf/README.md), and MuJoCo 2.2.2's broadphase costs O(bodies^2) per step even with no
  // contact: at 1000 vehicles it is the largest single cost (docs/PERFORMANCE.md).
  bool contacts = true;
  // [[vehicles.fault]]: from `at` on, rotor `rotor` of follower `follower` gives only
  // (1 - thrust_share) of the thrust its (clamped) command asks for.
  struct RotorFault {
    int follower = 1;  // 1-based, as in the file
    int rotor = 0;     // the attitude plugin's actuator order
    double at = 0.0;   // s
    double thrust_share = 0.0;
    int line = 0;
  };
  std::vector<RotorFault> rotor_faults;
  // Bring your own quadrotor (docs/VEHICLES.md): the model's vehicle body and rotor actuators,
  // in the attitude plugin's order. Empty body and rotors: the model follows the contract.
  std::string vehicle_body;
  std::vector<std::string> vehicle_rotors;
  ValueOrigin vehicle_body_origin, vehicle_rotors_origin;  // for messages
  // Thrust-and-moment vehicles ([vehicles] thrust = "...", moments = ["...", "...", "..."]):
  // vehicle_rotors then holds the four actuators in the plugin's order (thrust, moment x, y, z)
  // and vehicle_rotors_origin the origin of `thrust`.
  VehicleActuation vehicle_actuation = VehicleActuation::kRotors;
  ValueOrigin vehicle_moments_origin;

  // [topology]
  std::vector<double> leader_weight;  // a_i0 per follower (0-based)
  struct Edge {
    int from = 0;  // 0-based follower
    int to = 0;
    double weight = 1.0;
  };
  std::vector<Edge> edges;
  // [[topology.switch]]: from `at` on, the formation law sees this graph instead (docs/
  // EXPERIMENT_FILE.md); sorted by time, each with a directed spanning tree rooted at the leader.
  struct TopologySwitch {
    double at = 0.0;                    // s
    std::vector<double> leader_weight;  // a_i0 per follower (0-based)
    std::vector<Edge> edges;
    int line = 0;  // of the switch's table, for messages
  };
  std::vector<TopologySwitch> topology_switches;

  PluginSection leader;
  PluginSection formation;
  PluginSection attitude;
  PluginSection estimator;  // [estimator]: per vehicle, default "passthrough"
  ShapeConfig shape;
  RenderConfig render;
  SensorsConfig sensors;  // [sensors] (realism_config.hpp)
  WindConfig wind;        // [wind]
  NetworkConfig network;  // [execution] + [network]
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_EXPERIMENT_HPP_
