// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One simulation: the composed model, its data, the plugin instances and the stepping loop
// mj_step1 -> sensors -> guidance -> formation -> attitude -> controls -> mj_step2.
// Everything a run can get wrong in its input is checked in the constructor, before any step.
#ifndef MJFORMATION_RUNNER_SIMULATION_HPP_
#define MJFORMATION_RUNNER_SIMULATION_HPP_

#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/realism/sensor_model.hpp"
#include "mjformation/realism/wind_field.hpp"
#include "mjformation/runner/config.hpp"
#include "mjformation/runner/plugin_host.hpp"

namespace mjf::core {
class Graph;
class Shape;
}  // namespace mjf::core

namespace mjf::runner {

// The simulation went wrong mid-run (non-finite state, MuJoCo warning, plugin error).
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where vehicle i's sensor values and actuators live in the composed model.
struct VehicleBinding {
  int body = -1;
  int sensor_pos = -1, sensor_vel = -1, sensor_quat = -1, sensor_gyro = -1;  // sensordata adr
  std::vector<int> actuators;  // ids in the composed model (actuator rotor model)
  std::vector<int> sites;      // site of each driven actuator (wrench rotor model)
  std::vector<mjfActuatorInfo> actuator_info;
  mjfVehicleInfo info{};
};

class Simulation {
 public:
  // Composes the scene, compiles it, binds sensors and actuators, loads and creates the plugins.
  // Throws ConfigError / SceneError / PluginError with messages naming file, line and key.
  explicit Simulation(const ExperimentConfig& config);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Computes sensors (mj_step1) and runs every plugin for the current state; the controls are
  // then in d->ctrl (or in the rotor wrench). Throws SimulationError.
  void ComputeControls();
  // Integrates one step (mj_step2, or mj_step's second half for the wrench model) and checks
  // the new state: non-finite values or MuJoCo warnings throw SimulationError.
  void Integrate();

  const ExperimentConfig& config() const { return config_; }
  const mjModel* model() const { return model_; }
  mjData* data() { return data_; }
  const mjData* data() const { return data_; }
  const std::string& scene_xml() const { return scene_xml_; }
  int64_t step_index() const { return step_; }
  int64_t total_steps() const { return total_steps_; }
  double time() const { return static_cast<double>(step_) * config_.timestep; }
  int n_vehicles() const { return static_cast<int>(states_.size()); }
  int n_followers() const { return n_vehicles() - 1; }
  const std::vector<mjfVehicleState>& states() const { return states_; }
  const std::vector<mjfSetpoint>& setpoints() const { return setpoints_; }
  const std::vector<double>& controls() const { return controls_; }  // per vehicle, per actuator
  int actuators_per_vehicle() const { return actuators_per_vehicle_; }
  const VehicleBinding& binding(int vehicle) const { return bindings_[vehicle]; }
  // The desired formation (nullptr when [formation.shape] type = "none").
  const core::Shape* shape() const { return shape_.get(); }
  const PluginInstance& leader_plugin() const { return *leader_; }
  const PluginInstance* formation_plugin() const { return formation_.get(); }
  const PluginInstance& attitude_plugin(int vehicle) const { return *attitude_[vehicle]; }
  const PluginRegistry& registry() const { return *registry_; }
  // The formation plugin's scalar report ("delta", "error_bound", ...), if any.
  std::vector<std::pair<std::string, double>> FormationReport() const;

  // --- Sensor and wind stages (issue 11) ---
  // What the plugins saw this step: the sensor model's output, or the truth (states()) when
  // [sensors] is ideal.
  const std::vector<mjfVehicleState>& measured_states() const {
    return sensors_.empty() ? states_ : measured_;
  }
  // The wind at each vehicle this step (m/s, world); empty when [wind] is calm.
  const std::vector<std::array<double, 3>>& wind() const { return wind_now_; }

 private:
  void BindVehicles(const mjfPlugin& attitude);
  void CreatePlugins();
  void ReadStates();
  void ApplyRotorWrenches();
  void CheckState() const;
  std::string TimeTag() const;  // "t = 1.234 s", for messages
  // --- Sensor and wind stages (issue 11) ---
  void CreateRealismStages();  // none when [sensors] is ideal and [wind] calm
  void MeasureStates();        // states_ -> measured_ (the sensor stage)
  void ApplyWind();            // drag force at each vehicle's centre of mass, into qfrc_applied

  ExperimentConfig config_;
  std::unique_ptr<PluginRegistry> registry_;
  std::string scene_xml_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  // Owners of model_ and data_, so that a constructor that throws (bad plugin configuration,
  // topology, ...) frees them; declared before the plugins, so plugins go first.
  struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  std::unique_ptr<mjModel, ModelDeleter> model_owner_;
  std::unique_ptr<mjData, DataDeleter> data_owner_;
  int64_t step_ = 0;
  int64_t total_steps_ = 0;

  std::vector<VehicleBinding> bindings_;
  std::vector<std::array<double, 3>> initial_positions_;
  std::vector<mjfVehicleState> states_;
  std::vector<mjfSetpoint> setpoints_;
  std::vector<double> controls_;
  std::vector<double> rotor_state_;  // wrench rotor model: motor lag states, like MuJoCo's act
  std::vector<double> wrench_gain_;  // wrench rotor model: actuator gain per driven actuator
  int actuators_per_vehicle_ = 0;

  std::unique_ptr<core::Graph> graph_;
  std::unique_ptr<core::Shape> shape_;
  mjfGraph abi_graph_{};
  mjfShape abi_shape_{};
  std::vector<int> edge_from_, edge_to_;
  std::vector<double> edge_weight_;

  std::unique_ptr<PluginInstance> leader_;
  std::unique_ptr<PluginInstance> formation_;                       // formation-kind plugin, or
  std::vector<std::unique_ptr<PluginInstance>> follower_guidance_;  // a guidance per follower
  std::vector<std::unique_ptr<PluginInstance>> attitude_;

  // --- Sensor and wind stages (issue 11) ---
  std::vector<realism::SensorModel> sensors_;  // per vehicle; empty: ideal
  std::vector<mjfVehicleState> measured_;
  std::unique_ptr<realism::WindField> wind_;  // null: calm
  std::vector<std::array<double, 3>> wind_now_;
};

// Euler angles (roll, pitch, yaw; ZYX convention, rad) of a w-x-y-z quaternion.
std::array<double, 3> EulerZYX(const double quat[4]);

}  // namespace mjf::runner

#endif  // MJFORMATION_RUNNER_SIMULATION_HPP_
