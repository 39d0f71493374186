// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "adapt/vehicle_sensors.hpp"

#include <mujoco/mujoco.h>

#include <array>
#include <cstdio>

#include "mjformation/scene/scene.hpp"
#include "mjspec_util.hpp"

namespace mjf::runner {
namespace {

// The centre of mass of `vehicle`'s subtree in the body's axes, from the spec as it stands.
std::array<double, 3> CentreOfMass(mjSpec* s, const std::string& label) {
  mjModel* m = mj_compile(s, nullptr);
  if (!m) throw SceneError(label + ": MuJoCo cannot load the model: " + mjs_getError(s));
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  const int b = mj_name2id(m, mjOBJ_BODY, "vehicle");
  double rel[3];
  std::array<double, 3> com;
  mju_sub3(rel, d->subtree_com + 3 * b, d->xpos + 3 * b);
  mju_mulMatTVec(com.data(), d->xmat + 9 * b, rel, 3, 3);  // world offset -> body axes: R^T rel
  mj_deleteData(d);
  mj_deleteModel(m);
  return com;
}

// The site is made as the MJCF element <site name="imu" .../> inside the body was: from the
// body's childclass (else the main class), then its own attributes.
void AddImuSite(mjSpec* s, mjsBody* body, const std::array<double, 3>& com) {
  const std::string childclass = spec::Str(body->childclass);
  const mjsDefault* def =
      childclass.empty() ? mjs_getSpecDefault(s) : mjs_findDefault(s, childclass.c_str());
  mjsSite* site = mjs_addSite(body, def);
  mjs_setName(site->element, "imu");
  for (int k = 0; k < 3; ++k) site->pos[k] = com[k];
  site->quat[0] = 1;
  site->quat[1] = site->quat[2] = site->quat[3] = 0;
  site->size[0] = 0.005;
  site->group = 5;  // not drawn by default
}

}  // namespace

std::string AddImuAndSensors(const std::string& xml, const std::string& label,
                             std::vector<std::string>* notes) {
  const spec::SpecPtr s = spec::Parse(label, xml, label, "adapted model");
  mjsBody* body = mjs_findBody(s.get(), "vehicle");
  if (!body) throw SceneError(label + ": no body 'vehicle'");
  const std::array<double, 3> com = CentreOfMass(s.get(), label);
  AddImuSite(s.get(), body, com);
  char pos[128];
  std::snprintf(pos, sizeof(pos), "%.17g %.17g %.17g", com[0], com[1], com[2]);
  notes->push_back(std::string("added site 'imu' at the centre of mass (") + pos +
                   " in body axes)");
  const struct {
    mjtSensor type;
    const char* name;
  } kinds[] = {{mjSENS_FRAMEPOS, "pos"},
               {mjSENS_FRAMELINVEL, "vel"},
               {mjSENS_FRAMEQUAT, "quat"},
               {mjSENS_GYRO, "gyro"}};
  for (const auto& k : kinds) {
    mjsSensor* sensor = mjs_addSensor(s.get());
    mjs_setName(sensor->element, k.name);
    sensor->type = k.type;
    sensor->objtype = mjOBJ_SITE;
    mjs_setString(sensor->objname, "imu");
  }
  notes->push_back("added sensors pos, vel, quat, gyro at site 'imu'");
  return spec::SaveXml(s.get(), label);
}

}  // namespace mjf::runner
