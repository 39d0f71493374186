// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// kf_ins: the adapter of KfIns (src/kf_ins.cc). Per step: the accelerometer sample rotated into
// the world frame by the attitude channel propagates the filter, every arrived measurement is
// fused at the time it was taken, and the estimate for now is written (attitude and body rate
// are the attitude and body-rate channels: this filter does not estimate them).
#include "mjformation/estimator/kf_ins.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mjformation/plugin_util.hpp>
#include <string>

#include "adapter.hpp"

namespace mjf::estimator::adapter {
namespace {

using mjf::plugin::Attributes;
using mjf::plugin::ConfigError;

const mjfAttribute kKfInsAttributes[] = {
    {"accel_noise", "", "m/s^2/sqrt(Hz): white specific-force noise assumed (empty: the suite's)"},
    {"accel_bias_walk", "", "m/s^3/sqrt(Hz): bias random walk assumed (empty: the suite's)"},
    {"gate_sigma", "5", "innovation gate, standard deviations per axis"},
    {"initial_position_std", "1", "m: initial position uncertainty (about the start position)"},
    {"initial_velocity_std", "0.5", "m/s: initial velocity uncertainty (about rest)"},
    {"initial_bias_std", "0.2", "m/s^2: initial accelerometer bias uncertainty"},
    {"position_wander", "",
     "m: the position source's Gauss-Markov wander, estimated as a state (empty: the suite's; "
     "0: none, every sample's stated accuracy fused as white noise)"},
    {"position_wander_tau", "", "s: the wander's correlation time (empty: the suite's)"},
};

// The longest history KfIns keeps (its bound, checked here to name the sensor keys that set it).
constexpr double kMaxHistory = 10.0;

// v rotated from body to world by the unit quaternion q (w x y z): v + 2 w (u x v) + 2 u x (u x v).
Vec3 Rotate(const double q[4], const double v[3]) {
  const Vec3 u(q[1], q[2], q[3]);
  const Vec3 x(v[0], v[1], v[2]);
  const Vec3 t = 2.0 * u.cross(x);
  return x + q[0] * t + u.cross(t);
}

// A standard deviation (or noise density) the filter squares into its covariance: a number in
// [0, max], in the key's unit, so every variance it forms stays finite and a negative one is not
// silently squared into a positive one.
double Bounded(const Attributes& a, const char* key, double max, const char* unit) {
  const double v = a.Number(key);
  if (!(v >= 0 && v <= max)) {
    char range[64];
    std::snprintf(range, sizeof(range), "[0, %g] ", max);
    throw ConfigError(std::string("attribute '") + key + "': must be a number in " + range + unit +
                      ", got " + a.String(key));
  }
  return v;
}

double OrSuite(const Attributes& a, const char* key, double suite, double max, const char* unit) {
  const std::string text = a.String(key);
  return text.empty() ? suite : Bounded(a, key, max, unit);
}

KfInsConfig ReadConfig(const mjfCreateContext* ctx) {
  const mjfSensorInfo* s = ctx->sensors;
  if (!s) throw ConfigError("the host gave no sensor suite (not an estimator context)");
  if (!s->has_accel) {
    throw ConfigError(
        "needs an accelerometer channel ([sensors] accel_*; the vehicle's contract "
        "sensor 'accel')");
  }
  if (!(s->position_sources & MJF_MEASURES_POSITION)) {
    throw ConfigError("needs a position source ([sensors] gnss / rtk / mocap, or position_*)");
  }
  const Attributes a(ctx);
  KfInsConfig c;
  c.timestep = ctx->timestep;
  // The bounds are the sensor suite's ([sensors] accel_noise, accel_bias_walk, position_std).
  c.accel_noise_density = OrSuite(a, "accel_noise", s->accel_noise_density, 100, "m/s^2/sqrt(Hz)");
  c.accel_bias_walk = OrSuite(a, "accel_bias_walk", s->accel_bias_walk, 10, "m/s^3/sqrt(Hz)");
  c.gate_sigma = a.Number("gate_sigma");
  if (!(c.gate_sigma > 0)) throw ConfigError("attribute 'gate_sigma': must be > 0 (sigmas)");
  c.history = s->max_latency + 2.0 * ctx->timestep;
  if (!(c.history <= kMaxHistory)) {
    char what[256];
    std::snprintf(what, sizeof(what),
                  "the sensors' largest aiding latency (%g s, [sensors] position_latency / "
                  "velocity_latency) is past the %g s of history the filter keeps: lower it",
                  s->max_latency, kMaxHistory - 2.0 * ctx->timestep);
    throw ConfigError(what);
  }
  // Only the schedule's steps are kept (a sample is never taken between them).
  c.aiding_period = s->aiding_period;
  c.gravity = ctx->vehicle_info ? ctx->vehicle_info->gravity : 9.81;
  if (ctx->initial_pos)
    c.initial_position = Vec3(ctx->initial_pos[0], ctx->initial_pos[1], ctx->initial_pos[2]);
  c.initial_position_std = Bounded(a, "initial_position_std", 1e4, "m");
  c.initial_velocity_std = Bounded(a, "initial_velocity_std", 1e3, "m/s");
  c.initial_bias_std = Bounded(a, "initial_bias_std", 100, "m/s^2");
  c.position_wander_std = OrSuite(a, "position_wander", s->position_wander_std, 1000, "m");
  const std::string tau = a.String("position_wander_tau");
  c.position_wander_tau = tau.empty() ? s->position_wander_tau : a.Number("position_wander_tau");
  if (!(c.position_wander_std >= 0) || !std::isfinite(c.position_wander_std)) {
    throw ConfigError("attribute 'position_wander': must be a finite number >= 0 m");
  }
  if (c.position_wander_std == 0) {
    c.position_wander_tau = 100.0;  // unused without a wander (a suite without one may say 0)
  } else if (!(c.position_wander_tau > 0) || !std::isfinite(c.position_wander_tau)) {
    throw ConfigError("attribute 'position_wander_tau': must be a finite number > 0 s");
  }
  return c;
}

struct KfInsInstance {
  explicit KfInsInstance(const mjfCreateContext* ctx)
      : filter(ReadConfig(ctx)),
        accel_in_world(ctx->sensors->accel_in_world != 0),
        suite_wander_variance(ctx->sensors->position_wander_std *
                              ctx->sensors->position_wander_std),
        wander_is_a_state(filter.config().position_wander_std > 0) {}
  KfIns filter;
  bool accel_in_world;
  // A measurement states sqrt(white^2 + wander^2); with the wander a state, only the white part
  // is measurement noise.
  double suite_wander_variance;
  bool wander_is_a_state;
  template <typename Visit>
  void VisitState(Visit& visit) {
    filter.VisitState(visit);
  }
};

void* KfInsCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* { return new KfInsInstance(ctx); });
}

// The white part of a stated position accuracy (the wander taken out when the filter estimates
// it); a sensor is never exact (KfIns floors it at 1 um).
double WhitePart(double stated, double wander_variance) {
  return std::sqrt(std::max(stated * stated - wander_variance, 0.0));
}

AidingSample ToSample(const mjfMeasurement& m, const KfInsInstance& self) {
  AidingSample s;
  s.time_taken = m.time_taken;
  s.has_position = (m.fields & MJF_MEASURES_POSITION) != 0;
  s.has_velocity = (m.fields & MJF_MEASURES_VELOCITY) != 0;
  s.position = Vec3(m.pos[0], m.pos[1], m.pos[2]);
  s.velocity = Vec3(m.vel[0], m.vel[1], m.vel[2]);
  const double wander = self.wander_is_a_state ? self.suite_wander_variance : 0.0;
  s.position_std = Vec3(WhitePart(m.pos_std[0], wander), WhitePart(m.pos_std[1], wander),
                        WhitePart(m.pos_std[2], wander));
  s.velocity_std = Vec3(m.vel_std[0], m.vel_std[1], m.vel_std[2]);
  return s;
}

// Attitude and body rate: the channels' current samples (imu.quat is the one of the interval the
// accelerometer sample covers, a step older).
void WriteEstimate(const KfIns& f, const mjfVehicleState& now, mjfEstimate* out) {
  const Vec3 p = f.position(), v = f.velocity();
  for (int k = 0; k < 3; ++k) {
    out->state.pos[k] = p[k];
    out->state.vel[k] = v[k];
    out->state.gyro[k] = now.gyro[k];
  }
  for (int k = 0; k < 4; ++k) out->state.quat[k] = now.quat[k];
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out->covariance[6 * r + c] = f.covariance()(r, c);
  }
  out->fused = f.fused();
  out->rejected = f.rejected();
}

int KfInsCompute(void* instance, const mjfStepContext* ctx) {
  return mjf::plugin::ComputeOrExplain(ctx, [&] {
    auto* self = static_cast<KfInsInstance*>(instance);
    const mjfEstimatorInput& in = *ctx->estimator;
    if (ctx->step > 0) {
      const Vec3 f = self->accel_in_world ? Vec3(in.imu.accel[0], in.imu.accel[1], in.imu.accel[2])
                                          : Rotate(in.imu.quat, in.imu.accel);
      self->filter.Propagate(ctx->step, f);
    }
    for (int k = 0; k < in.n_measurements; ++k)
      self->filter.Fuse(ToSample(in.measurements[k], *self));
    WriteEstimate(self->filter, *in.held, ctx->estimate);
    return 0;
  });
}

void KfInsReport(void* instance, mjfReportFn emit, void* user) {
  const KfIns& f = static_cast<KfInsInstance*>(instance)->filter;
  emit(user, "fused", static_cast<double>(f.fused()));
  emit(user, "gated", static_cast<double>(f.rejected()));
  emit(user, "too_old", static_cast<double>(f.too_old()));
}

}  // namespace

const mjfPlugin kKfIns = EstimatorPlugin<KfInsInstance>(
    "kf_ins",
    "world-frame Kalman filter (p, v, accel bias, GNSS wander), IMU input, delayed fusion, 5-sigma "
    "gate",
    kKfInsAttributes, KfInsCreate, KfInsCompute, KfInsReport);

}  // namespace mjf::estimator::adapter
