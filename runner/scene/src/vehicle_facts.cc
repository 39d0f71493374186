// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/vehicle_facts.hpp"

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace mjf::runner {
namespace {

std::string Name(const mjModel* m, mjtObj type, int id) {
  const char* name = mj_id2name(m, type, id);
  return name ? name : "";
}

// A body's frame as mj_kinematics computes it (xpos, xquat, xmat).
struct Frame {
  mjtNum pos[3], quat[4], mat[9];
};

// The vehicle's body where its own model puts it (body_pos, body_quat): where mj_kinematics
// places a body whose parent is the world, or a free body at qpos0. The arms are then read as
// the runner always read them, R^T (site_xpos - xipos) after mj_forward of the vehicle model, to
// the last bit (its bytes stay), with no mjData: a native plugin's init cannot make one.
Frame Placed(const mjModel* m, int body) {
  Frame f;
  mju_copy3(f.pos, m->body_pos + 3 * body);
  mju_copy4(f.quat, m->body_quat + 4 * body);
  mju_normalize4(f.quat);
  mju_quat2Mat(f.mat, f.quat);
  return f;
}

// Child body `b` of `parent`, fixed to it (no joint), with mj_kinematics' arithmetic.
Frame Child(const mjModel* m, const Frame& parent, int b) {
  Frame f;
  mju_mulMatVec3(f.pos, parent.mat, m->body_pos + 3 * b);
  mju_addTo3(f.pos, parent.pos);
  mju_mulQuat(f.quat, parent.quat, m->body_quat + 4 * b);
  mju_normalize4(f.quat);
  mju_quat2Mat(f.mat, f.quat);
  return f;
}

// Where `local` (in frame f) lies in f's parent: mj_local2Global's position.
void ToPlaced(const Frame& f, const mjtNum local[3], mjtNum out[3]) {
  mju_mulMatVec3(out, f.mat, local);
  mju_addTo3(out, f.pos);
}

// The bodies from the vehicle's body (excluded) down to `site`'s body: each must be fixed to its
// parent, or the rotor has no fixed arm; a site outside the vehicle has none either.
std::vector<int> FixedChain(const mjModel* m, int body, int site) {
  const std::string named = "a rotor acts on site '" + Name(m, mjOBJ_SITE, site) + "'";
  std::vector<int> chain;
  for (int b = m->site_bodyid[site]; b != body; b = m->body_parentid[b]) {
    if (b == 0) {
      throw VehicleFactError("actuators",
                             named + ", which is not on the vehicle's body or a body inside it");
    }
    if (m->body_jntnum[b] > 0) {
      throw VehicleFactError("actuators", named + " of body '" + Name(m, mjOBJ_BODY, b) +
                                              "', which a joint moves: a rotor's arm must be "
                                              "fixed to the body");
    }
    chain.insert(chain.begin(), b);
  }
  return chain;
}

// Rotor site `site` relative to the centre of mass of `body`, in body axes:
// R^T (site_xpos - xipos), both placed by mj_kinematics' arithmetic through the fixed chain.
void RotorArm(const mjModel* m, int body, int site, double out[3]) {
  const std::vector<int> chain = FixedChain(m, body, site);
  const Frame vehicle = Placed(m, body);
  Frame f = vehicle;
  for (int b : chain) f = Child(m, f, b);
  mjtNum site_x[3], com_x[3], rel[3];
  ToPlaced(f, m->site_pos + 3 * site, site_x);
  ToPlaced(vehicle, m->body_ipos + 3 * body, com_x);
  mju_sub3(rel, site_x, com_x);
  mju_mulMatTVec(out, vehicle.mat, rel, 3, 3);
}

// Actuator `a`'s gear, control range and motor lag. MuJoCo 4 keeps the per-actuator arrays by
// actuator id, the gear by force output (actuator_outadr) and the control range by control
// (actuator_ctrladr); a rotor has one of each.
mjfActuatorInfo ActuatorInfo(const mjModel* m, int a) {
  mjfActuatorInfo info{};
  const int out = m->actuator_outadr[a], ctrl = m->actuator_ctrladr[a];
  mju_copy(info.gear, m->actuator_gear + 6 * out, 6);
  const double inf = std::numeric_limits<double>::infinity();
  info.ctrl_min = m->actuator_ctrllimited[ctrl] ? m->actuator_ctrlrange[2 * ctrl] : -inf;
  info.ctrl_max = m->actuator_ctrllimited[ctrl] ? m->actuator_ctrlrange[2 * ctrl + 1] : inf;
  info.time_constant = m->actuator_dyntype[a] == mjDYN_FILTER ? m->actuator_dynprm[mjNDYN * a] : 0;
  return info;
}

int RequireActuator(const mjModel* m, const std::string& name) {
  const int a = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str());
  if (a < 0) {
    std::string have;
    for (int j = 0; j < m->nactuator; ++j)
      have += (have.empty() ? "" : ", ") + Name(m, mjOBJ_ACTUATOR, j);
    throw VehicleFactError("actuators", "no actuator named '" + name + "' in this model (it has: " +
                                            (have.empty() ? "none" : have) + ")");
  }
  if (m->actuator_ctrlnum[a] != 1 || m->actuator_outnum[a] != 1) {
    throw VehicleFactError(
        "actuators", "actuator '" + name + "' takes " + std::to_string(m->actuator_ctrlnum[a]) +
                         " controls and has " + std::to_string(m->actuator_outnum[a]) +
                         " force outputs; a rotor has one of each: name the "
                         "rotors");
  }
  return a;
}

// The body actuator `a` pulls on, or -1 when its transmission names none (a tendon).
int ActedOnBody(const mjModel* m, int a) {
  const int id = m->actuator_trnid[2 * a];
  switch (m->actuator_trntype[a]) {
    case mjTRN_JOINT:
    case mjTRN_JOINTINPARENT:
      return m->jnt_bodyid[id];
    case mjTRN_SITE:
    case mjTRN_SLIDERCRANK:
      return m->site_bodyid[id];
    case mjTRN_BODY:
      return id;
    case mjTRN_SO3:  // an orientation servo: of a ball joint, or of a site against a refsite
      return m->actuator_trnid[2 * a + 1] >= 0 ? m->site_bodyid[id] : m->jnt_bodyid[id];
    default:
      return -1;
  }
}

bool Inside(const mjModel* m, int b, int body) {
  for (; b > 0; b = m->body_parentid[b]) {
    if (b == body) return true;
  }
  return false;
}

// Every actuator on the vehicle's bodies that `facts` does not drive.
std::vector<std::string> Ignored(const mjModel* m, const VehicleFacts& facts) {
  std::vector<std::string> out;
  for (int a = 0; a < m->nactuator; ++a) {
    bool driven = false;
    for (int d : facts.actuators) driven |= d == a;
    const int b = ActedOnBody(m, a);
    if (!driven && b >= 0 && Inside(m, b, facts.body)) out.push_back(Name(m, mjOBJ_ACTUATOR, a));
  }
  return out;
}

// J_ii = sum_k R_ik^2 I_k, the diagonal of R(iquat) diag(I) R(iquat)^T.
void BodyAxisInertia(const mjModel* m, int body, double out[3]) {
  mjtNum r[9];
  mju_quat2Mat(r, m->body_iquat + 4 * body);
  const mjtNum* principal = m->body_inertia + 3 * body;
  for (int i = 0; i < 3; ++i) {
    out[i] = 0;
    for (int k = 0; k < 3; ++k) out[i] += r[3 * i + k] * r[3 * i + k] * principal[k];
  }
}

}  // namespace

VehicleFacts ReadVehicleFacts(const mjModel* m, const std::string& body_name,
                              const std::vector<std::string>& actuators) {
  VehicleFacts facts;
  facts.body = mj_name2id(m, mjOBJ_BODY, body_name.c_str());
  if (facts.body <= 0) {
    throw VehicleFactError("body", "no body named '" + body_name + "' in this model");
  }
  // A body no joint moves is welded to the world: a run would complete with it fixed in place.
  if (m->body_dofnum[facts.body] == 0) {
    throw VehicleFactError("body", "body '" + body_name +
                                       "' has no joint, so it is welded to the world: give it "
                                       "<freejoint/> (or the slide joints of mjcf/pointmass.xml)");
  }
  facts.mass = m->body_subtreemass[facts.body];
  BodyAxisInertia(m, facts.body, facts.inertia);
  for (const std::string& name : actuators) {
    const int a = RequireActuator(m, name);
    mjfActuatorInfo info = ActuatorInfo(m, a);
    const bool on_site = m->actuator_trntype[a] == mjTRN_SITE;
    if (on_site) RotorArm(m, facts.body, m->actuator_trnid[2 * a], info.site_pos);
    facts.actuators.push_back(a);
    facts.sites.push_back(on_site ? m->actuator_trnid[2 * a] : -1);
    facts.info.push_back(info);
    facts.gains.push_back(m->actuator_gainprm[mjNGAIN * a]);
  }
  facts.ignored = Ignored(m, facts);
  return facts;
}

int MisfitThrustMomentRole(const VehicleFacts& facts) {
  for (int k = 0; k < 4 && k < static_cast<int>(facts.info.size()); ++k) {
    const double* g = facts.info[k].gear;
    const int axis = ThrustMomentGearEntry(k);
    bool pure = g[axis] != 0;
    for (int i = 0; i < 6; ++i) pure &= i == axis || g[i] == 0;
    if (!pure) return k;
  }
  return -1;
}

const char* ThrustMomentRole(int k) {
  static const char* const kRole[] = {"thrust along body z", "moment about body x",
                                      "moment about body y", "moment about body z"};
  return kRole[k];
}

int ThrustMomentGearEntry(int k) { return k == 0 ? 2 : 2 + k; }

std::string GearText(const double gear[6]) {
  char text[160];
  std::snprintf(text, sizeof(text), "%g %g %g %g %g %g", gear[0], gear[1], gear[2], gear[3],
                gear[4], gear[5]);
  return text;
}

}  // namespace mjf::runner
