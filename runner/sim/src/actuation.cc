// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/actuation.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "mjformation/scene/rotor_faults.hpp"

namespace mjf::runner {
// The wrench rotor model: what MuJoCo's site transmission with a filter actuator would apply,
// computed per vehicle in O(1) instead of through the dense nu x nv actuator_moment of 2.2.2.
// force = gain * act (act: first-order motor lag of the clamped control, updated in Integrate);
// the wrench gear * force acts at the site, in the site's frame.
//
// The vehicle's summed wrench (force f at its centre of mass, torque t) goes to MuJoCo as the
// generalized force J^T [f; t] in qfrc_passive, computed here from cdof over the vehicle's own
// dofs only. Handing it over as xfrc_applied instead makes MuJoCo 2.2.2 (mj_xfrcAccumulate ->
// mj_applyFT) build and clear two dense 3 x nv Jacobians per vehicle every step: O(N nv) =
// O(N^2), 97% of a step at 1000 followers (docs/PERFORMANCE.md). The maths is mj_jac's: for each
// dof j of the body's chain, J_j . [f; t] = (cdof_lin + cdof_rot x (point - subtree_com)) . f +
// cdof_rot . t; only the floating-point summation order differs.
// The small vector helpers are written out in MuJoCo's own operation order (mju_mulMatVec,
// mju_cross, mju_dot3, without FMA), so the results are bit for bit those of the mju_* calls, at a
// fraction of the cost of calling through the shared library's PLT for every rotor of every
// vehicle on every step.
namespace {
inline void MulMat3Vec(mjtNum res[3], const mjtNum m[9], const mjtNum v[3]) {
  for (int r = 0; r < 3; ++r) res[r] = m[3 * r] * v[0] + m[3 * r + 1] * v[1] + m[3 * r + 2] * v[2];
}
inline void Cross(mjtNum res[3], const mjtNum a[3], const mjtNum b[3]) {
  res[0] = a[1] * b[2] - a[2] * b[1];
  res[1] = a[2] * b[0] - a[0] * b[2];
  res[2] = a[0] * b[1] - a[1] * b[0];
}
inline mjtNum Dot3(const mjtNum a[3], const mjtNum b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
}  // namespace

void AddWrenchAtCentreOfMass(const mjModel* m, mjData* d, int body, const mjtNum wrench[6]) {
  const mjtNum* com = d->xipos + 3 * body;
  // J^T wrench at the centre of mass, over the dofs that move this body (as mj_jac walks them).
  while (body && !m->body_dofnum[body]) body = m->body_parentid[body];
  if (!body) return;
  const mjtNum* root_com = d->subtree_com + 3 * m->body_rootid[body];
  mjtNum offset[3];
  for (int j = 0; j < 3; ++j) offset[j] = com[j] - root_com[j];
  for (int j = m->body_dofadr[body] + m->body_dofnum[body] - 1; j >= 0; j = m->dof_parentid[j]) {
    const mjtNum* cdof = d->cdof + 6 * j;
    mjtNum lin[3];
    Cross(lin, cdof, offset);
    for (int k = 0; k < 3; ++k) lin[k] += cdof[3 + k];
    d->qfrc_passive[j] += Dot3(lin, wrench) + Dot3(cdof, wrench + 3);
  }
}

namespace {

// MuJoCo's own actuators: the controls go to d->ctrl.
class ActuatorActuation final : public Actuation {
 public:
  explicit ActuatorActuation(const VehicleBindings& bindings) : bindings_(bindings) {}
  void Apply(const std::vector<double>& controls, mjData* data) override {
    const int per = bindings_.actuators_per_vehicle;
    for (size_t i = 0; i < bindings_.vehicles.size(); ++i) {
      const VehicleBinding& b = bindings_.vehicles[i];
      const double* c = controls.data() + i * per;
      for (int k = 0; k < per; ++k) data->ctrl[b.actuators[k]] = c[k];
    }
  }
  void Advance(const std::vector<double>&) override {}

 private:
  const VehicleBindings& bindings_;
};

// The wrench rotor model (see the comment above AddWrenchAtCentreOfMass's helpers).
class WrenchActuation final : public Actuation {
 public:
  WrenchActuation(const mjModel* m, const VehicleBindings& bindings, double timestep)
      : model_(m),
        per_(bindings.actuators_per_vehicle),
        timestep_(timestep),
        axial_(AllAxial(bindings)),
        rotors_(Flattened(bindings)),
        rotor_state_(rotors_.size(), 0.0) {
    for (const VehicleBinding& b : bindings.vehicles) bodies_.push_back(b.body);
  }
  void Apply(const std::vector<double>& controls, mjData* data) override;
  void Advance(const std::vector<double>& controls) override;
  void VisitState(StateArchive& archive) override { archive(rotor_state_); }
  void VisitState(FixedStateArchive& archive) override { archive(rotor_state_); }

 private:
  // What the step reads of one driven actuator, [vehicle][actuator] like the controls: one
  // contiguous pass per step instead of three heap vectors per vehicle (the binding's sites and
  // actuator info, the shared gains), whose scattered reads cost more than their arithmetic.
  struct Rotor {
    double gain;  // actuator gain (wrench_gain)
    double ctrl_min, ctrl_max, time_constant;
    double gear[6];
    int site;
  };
  static std::vector<Rotor> Flattened(const VehicleBindings& bindings) {
    std::vector<Rotor> rotors;
    for (const VehicleBinding& b : bindings.vehicles) {
      for (int k = 0; k < bindings.actuators_per_vehicle; ++k) {
        const mjfActuatorInfo& a = b.actuator_info[k];
        Rotor r{bindings.wrench_gain[k], a.ctrl_min, a.ctrl_max, a.time_constant, {}, b.sites[k]};
        std::copy(a.gear, a.gear + 6, r.gear);
        rotors.push_back(r);
      }
    }
    return rotors;
  }

  // Summed rotor wrench of vehicle i about its centre of mass, world frame.
  void VehicleWrench(int i, const std::vector<double>& controls, const mjData* data,
                     mjtNum wrench[6]) const;

  // True when every rotor's gear acts along its site's z axis only: [0, 0, g, 0, 0, c].
  static bool AllAxial(const VehicleBindings& bindings) {
    for (const VehicleBinding& b : bindings.vehicles) {
      for (const mjfActuatorInfo& a : b.actuator_info) {
        if (a.gear[0] != 0 || a.gear[1] != 0 || a.gear[3] != 0 || a.gear[4] != 0) return false;
      }
    }
    return true;
  }

  const mjModel* model_;
  int per_;  // actuators per vehicle
  double timestep_;
  bool axial_;                       // AllAxial: the rotors' wrenches need one column of xmat
  std::vector<Rotor> rotors_;        // [vehicle][actuator]
  std::vector<int> bodies_;          // [vehicle]
  std::vector<double> rotor_state_;  // motor lag states, like MuJoCo's act
};

void WrenchActuation::VehicleWrench(int i, const std::vector<double>& controls, const mjData* data,
                                    mjtNum wrench[6]) const {
  const mjtNum* com = data->xipos + 3 * bodies_[i];
  const size_t base = static_cast<size_t>(i) * per_;
  for (int k = 0; k < per_; ++k) {
    const Rotor& a = rotors_[base + k];
    // force = gain * act (act: first-order motor lag of the clamped control, see Advance).
    const double force =
        a.gain * (a.time_constant > 0 ? rotor_state_[base + k]
                                      : std::clamp(controls[base + k], a.ctrl_min, a.ctrl_max));
    const mjtNum* xmat = data->site_xmat + 9 * a.site;
    const mjtNum* xpos = data->site_xpos + 3 * a.site;
    mjtNum f[3], t[3], arm[3], moment[3];
    if (axial_) {
      // xmat [0, 0, g force] (and [0, 0, c force]) without the two products by exact zeros:
      // MulMat3Vec's row sum (m0 * 0 + m1 * 0) + m2 * l is m2 * l bit for bit when m2 * l is
      // not zero (x + 0 = x), and when it is, the two differ at most in the sign of a zero, which
      // the sums below, started from +0, never keep (+0 + -0 = +0): the wrench's bits are equal.
      const mjtNum lz = a.gear[2] * force, tz = a.gear[5] * force;
      for (int r = 0; r < 3; ++r) {
        f[r] = xmat[3 * r + 2] * lz;
        t[r] = xmat[3 * r + 2] * tz;
      }
    } else {
      mjtNum local[3];
      for (int j = 0; j < 3; ++j) local[j] = a.gear[j] * force;
      MulMat3Vec(f, xmat, local);
      for (int j = 0; j < 3; ++j) local[j] = a.gear[3 + j] * force;
      MulMat3Vec(t, xmat, local);
    }
    for (int j = 0; j < 3; ++j) arm[j] = xpos[j] - com[j];
    Cross(moment, arm, f);
    for (int j = 0; j < 3; ++j) {
      wrench[j] += f[j];
      wrench[3 + j] += t[j] + moment[j];
    }
  }
}

void WrenchActuation::Apply(const std::vector<double>& controls, mjData* data) {
  for (size_t i = 0; i < bodies_.size(); ++i) {
    mjtNum wrench[6] = {0, 0, 0, 0, 0, 0};
    VehicleWrench(static_cast<int>(i), controls, data, wrench);
    AddWrenchAtCentreOfMass(model_, data, bodies_[i], wrench);
  }
}

void WrenchActuation::Advance(const std::vector<double>& controls) {
  // Motor lag, integrated like MuJoCo's filter dynamics: act += dt (ctrl - act) / tau.
  for (size_t idx = 0; idx < rotors_.size(); ++idx) {
    const Rotor& a = rotors_[idx];
    if (a.time_constant <= 0) continue;
    const double ctrl = std::clamp(controls[idx], a.ctrl_min, a.ctrl_max);
    rotor_state_[idx] += timestep_ * (ctrl - rotor_state_[idx]) / a.time_constant;
  }
}

// [[vehicles.fault]]: the faulty rotors' controls scaled (rotor_faults.hpp), then handed to the
// rotor model.
class FaultedActuation final : public Actuation {
 public:
  FaultedActuation(std::unique_ptr<Actuation> inner, std::vector<BoundRotorFault> faults,
                   double timestep)
      : inner_(std::move(inner)), faults_(std::move(faults)), timestep_(timestep) {}
  void Apply(const std::vector<double>& controls, mjData* data) override {
    faulted_ = controls;  // same size every step: no allocation after the first
    ApplyRotorFaults(faults_, data->time, timestep_, faulted_.data());
    inner_->Apply(faulted_, data);
  }
  // The controls of this step's Apply, faults included (the wrench model's motor lag).
  void Advance(const std::vector<double>&) override { inner_->Advance(faulted_); }
  // The faults are a function of time: the state is the rotor model's (the wrench model's lags).
  void VisitState(StateArchive& archive) override { inner_->VisitState(archive); }
  void VisitState(FixedStateArchive& archive) override { inner_->VisitState(archive); }

 private:
  std::unique_ptr<Actuation> inner_;
  std::vector<BoundRotorFault> faults_;
  double timestep_;
  std::vector<double> faulted_;
};

}  // namespace

std::unique_ptr<Actuation> WithRotorFaults(std::unique_ptr<Actuation> inner,
                                           const ExperimentConfig& config,
                                           const VehicleBindings& bindings, int first_vehicle) {
  std::vector<BoundRotorFault> faults = BindRotorFaults(config, bindings, first_vehicle);
  if (faults.empty()) return inner;
  return std::make_unique<FaultedActuation>(std::move(inner), std::move(faults), config.timestep);
}

std::unique_ptr<Actuation> MakeActuation(RotorModel model, const mjModel* m,
                                         const VehicleBindings& bindings, double timestep) {
  if (model == RotorModel::kWrench) return std::make_unique<WrenchActuation>(m, bindings, timestep);
  return std::make_unique<ActuatorActuation>(bindings);
}

}  // namespace mjf::runner
