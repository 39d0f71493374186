// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// example_orbit: a guidance plugin (one instance per vehicle) that flies its vehicle on a circle
// of `radius` m about its start position at `omega` rad/s, by feedforward centripetal
// acceleration plus a PD correction on the reference. It shows the pieces a plugin written
// against the installed mjformation needs: the ABI (mjformation/plugin.h), typed attributes and
// exception-safe create/compute (mjformation/plugin_util.hpp), and MJF_EXPORT_PLUGINS. Built
// against plugin ABI 4 (MJF_ABI_VERSION); a library built for another version is refused.
#include <mjformation/plugin.h>

#include <cmath>
#include <mjformation/plugin_util.hpp>

namespace {

using mjf::plugin::Attributes;

class Orbit {
 public:
  explicit Orbit(const mjfCreateContext* ctx)
      : vehicle_(ctx->vehicle),
        cx_(ctx->initial_pos[0]),
        cy_(ctx->initial_pos[1]),
        z_(ctx->initial_pos[2]) {
    const Attributes a(ctx);
    radius_ = a.Number("radius");
    omega_ = a.Number("omega");
    kp_ = a.Number("kp");
    kd_ = a.Number("kd");
    mjf::plugin::Require(radius_ > 0, "radius", "> 0", radius_);
    mjf::plugin::Require(kp_ > 0 && kd_ > 0, "kp", "kp > 0 and kd > 0", kp_);
    cx_ -= radius_;  // the vehicle starts on the circle, at phase 0
  }

  int Compute(const mjfStepContext* ctx) const {
    const mjfVehicleState& s = ctx->states[vehicle_];
    if (!std::isfinite(s.pos[0]) || !std::isfinite(s.pos[1])) {
      return mjf::plugin::Fail(ctx, "example_orbit: non-finite vehicle position");
    }
    // Reference p(t) = c + r (cos wt, sin wt); v = p', a = p'' = -w^2 (p - c).
    const double phase = omega_ * ctx->time;
    const double px = cx_ + radius_ * std::cos(phase), py = cy_ + radius_ * std::sin(phase);
    const double vx = -radius_ * omega_ * std::sin(phase), vy = radius_ * omega_ * std::cos(phase);
    mjfSetpoint& sp = ctx->setpoints[vehicle_];
    sp.pos[0] = px;
    sp.pos[1] = py;
    sp.pos[2] = z_;
    sp.vel[0] = vx;
    sp.vel[1] = vy;
    sp.acc[0] = -omega_ * omega_ * (px - cx_) + kp_ * (px - s.pos[0]) + kd_ * (vx - s.vel[0]);
    sp.acc[1] = -omega_ * omega_ * (py - cy_) + kp_ * (py - s.pos[1]) + kd_ * (vy - s.vel[1]);
    return 0;
  }

 private:
  int vehicle_;
  double cx_, cy_, z_;
  double radius_ = 0, omega_ = 0, kp_ = 0, kd_ = 0;
};

const mjfAttribute kAttributes[] = {{"radius", "3", "m: circle radius"},
                                    {"omega", "0.5", "rad/s: angular rate"},
                                    {"kp", "1.5", "1/s^2: position gain"},
                                    {"kd", "2", "1/s: velocity gain"}};

void* Create(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [&] { return new Orbit(ctx); });
}
int Compute(void* instance, const mjfStepContext* ctx) {
  return mjf::plugin::ComputeOrExplain(ctx,
                                       [&] { return static_cast<Orbit*>(instance)->Compute(ctx); });
}
void Destroy(void* instance) { delete static_cast<Orbit*>(instance); }

const mjfPlugin kOrbit = {MJF_ABI_VERSION,
                          "example_orbit",
                          MJF_KIND_GUIDANCE,
                          "example plugin built with find_package(mjformation): circles its start",
                          4,
                          kAttributes,
                          0,
                          nullptr,
                          Create,
                          Compute,
                          nullptr,
                          Destroy,
                          nullptr,
                          nullptr,  // ABI 4: no state (a function of time and the state)
                          nullptr,
                          nullptr};

}  // namespace

MJF_EXPORT_PLUGINS(&kOrbit)
