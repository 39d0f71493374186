// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What one vehicle's controllers measure of its true state: per channel (position, velocity,
// attitude, body rate) white noise, a bias random walk, a sample rate with zero-order hold and a
// latency. Pure C++ (no MuJoCo): the runner calls Measure() once per physics step, between
// reading MuJoCo's sensors and the plugins. Seeded per vehicle; same seed, same bytes.
#ifndef MJFORMATION_REALISM_SENSOR_MODEL_HPP_
#define MJFORMATION_REALISM_SENSOR_MODEL_HPP_

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mjformation/plugin.h"
#include "mjformation/realism/gaussian.hpp"
#include "mjformation/realism/sensor_params.hpp"

namespace mjf::realism {

// An archive that can update only the changed part of a run of doubles (DoublesChanged).
template <typename Archive, typename = void>
inline constexpr bool kUpdatesChangedDoubles = false;
template <typename Archive>
inline constexpr bool
    kUpdatesChangedDoubles<Archive, std::void_t<decltype(std::declval<Archive&>().DoublesChanged(
                                        std::declval<double*>(), size_t{}, size_t{}, size_t{}))>> =
        true;

class SensorModel {
 public:
  // Params must pass Validate(timestep) (throws std::invalid_argument otherwise).
  // `common_seed` seeds the wander part shared by all vehicles (the same for every vehicle's
  // model), `own_seed` this vehicle's wander and accelerometer; the white/bias stream of `seed` is
  // unchanged by them (existing configurations keep their bytes).
  SensorModel(const SensorParams& params, double timestep, uint64_t seed,
              uint64_t own_seed = 0x6f776e, uint64_t common_seed = 0x636f6d);

  // The measurement at physics step `step` of the true state `truth`. Call once per step with
  // step = 0, 1, 2, ... (the latency buffer counts on it; throws std::logic_error otherwise).
  void Measure(int64_t step, const mjfVehicleState& truth, mjfVehicleState* measured);

  // The samples of the aiding channels (position, velocity) taken fresh in the last Measure(),
  // stamped with the step they report the truth of (step - latency).
  struct Fresh {
    Channel channel;
    int64_t taken_step;
    std::array<double, 3> value;
    double stated_std;  // sqrt(white^2 + wander^2): what the suite says of its accuracy
  };
  const std::vector<Fresh>& fresh() const { return fresh_; }
  // At most one of each aiding channel per step.
  static constexpr size_t kMaxFresh = 2;

  // The accelerometer over the step that ended at `step` (call after Measure of that step):
  // f = R(t_{n-1})^T (a - g), a = (v_n - v_{n-1}) / dt, exactly the integrator's acceleration,
  // plus noise; `quat_out` is the attitude channel's reading at t_{n-1}, which rotates it back.
  void Accelerometer(int64_t step, const mjfVehicleState& truth, const mjfVehicleState& measured,
                     double gravity, double accel_out[3], double quat_out[4]);

  // The current bias of a channel (for tests and diagnostics).
  const std::array<double, 3>& Bias(Channel c) const { return channels_[static_cast<int>(c)].bias; }

  // Everything Measure and Accelerometer carry from one step to the next, both ways, in a
  // length the constructor fixes (the control tick's state: runner/config's
  // FixedStateArchive): the noise streams, each channel's latency buffer, held sample, bias
  // walk, wander and phases; what the constructor fixes is not state.
  template <typename Archive>
  void VisitState(Archive& a) {
    a(normal_, next_step_, own_normal_, common_normal_, accel_bias_);
    a(previous_truth_, previous_measured_);
    for (auto& ch : channels_) {
      VisitHistory(a, ch);
      a(ch.held, ch.bias, ch.last_sample, ch.write_slot, ch.phase, ch.bias_count);
      a(ch.wander_own, ch.wander_common, ch.fresh);
    }
    // The fresh samples in slots of a fixed number (a state's length is fixed by the
    // configuration: the native MuJoCo plugin's plugin_state), the unused ones zero.
    std::array<Fresh, kMaxFresh> slots{};
    std::copy(fresh_.begin(), fresh_.end(), slots.begin());
    uint64_t fresh = fresh_.size();
    a(fresh);
    for (auto& f : slots) a(f.channel, f.taken_step, f.value, f.stated_std);
    if (fresh > kMaxFresh) throw std::invalid_argument("sensor model: a foreign saved state");
    fresh_.assign(slots.begin(), slots.begin() + static_cast<ptrdiff_t>(fresh));
  }

 private:
  struct ChannelState {
    ChannelNoise noise;
    int dim = 3;                   // 4 for the attitude quaternion
    int64_t period_steps = 1;      // steps between samples
    int64_t latency_steps = 0;     // steps of delay
    std::vector<double> history;   // ring buffer of (latency + 1) truths, dim values each
    std::array<double, 4> held{};  // the last sample (dim values), true value + errors
    std::array<double, 3> bias{};  // current bias, per axis
    int64_t last_sample = -1;      // truth step of the held sample
    // Counters instead of step % n (integer division was most of a channel's cost per step).
    int64_t write_slot = 0;  // where this step's truth goes in history
    // How many truths went in since the state was last walked (not state: what a block updated
    // in place still lacks; the last one went to the slot before write_slot).
    int written_since_walk = 2;
    int64_t phase = 0;  // steps since the last sample, once the delay has passed
    // The bias walks every `bias_every` samples (at least every 10 ms: a drift that matters over
    // seconds need not cost three normal draws per 1 kHz gyro sample); var(b) = q^2 t at those
    // times, held in between.
    int64_t bias_every = 1, bias_count = 0;
    double wander_phi = 0.0;  // exp(-T / tau)
    std::array<double, 3> wander_own{}, wander_common{};
    bool fresh = false;  // a new sample in this step
  };
  void StepChannel(ChannelState& ch, int64_t step, const double* truth);
  // A channel's latency buffer: whole, but for an archive that updates a block holding the
  // buffer as the last walk that read or wrote a block left it (the native plugin, every step),
  // which gets the one slot written since (FixedStateArchive::DoublesChanged). A walk that only
  // counts (Sizing) leaves the count of slots written as it was.
  template <typename Archive>
  static void VisitHistory(Archive& a, ChannelState& ch) {
    if constexpr (kUpdatesChangedDoubles<Archive>) {
      const size_t dim = static_cast<size_t>(ch.dim);
      const int64_t written = ch.write_slot == 0 ? ch.latency_steps : ch.write_slot - 1;
      a.DoublesChanged(ch.history.data(), ch.history.size(), static_cast<size_t>(written) * dim,
                       ch.written_since_walk == 1 ? dim : ch.history.size() + 1);
      if (a.sizing()) return;
    } else {
      a(ch.history);
    }
    ch.written_since_walk = 0;
  }
  void StepWander(ChannelState& ch, bool first, double error[3]);

  bool ideal_;
  double timestep_;
  Gaussian normal_;
  std::array<ChannelState, kChannels> channels_;
  int64_t next_step_ = 0;
  Gaussian own_normal_, common_normal_;  // wander and accelerometer streams
  std::vector<Fresh> fresh_;
  AccelNoise accel_;
  std::array<double, 3> accel_bias_{};
  mjfVehicleState previous_truth_{}, previous_measured_{};
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_SENSOR_MODEL_HPP_
