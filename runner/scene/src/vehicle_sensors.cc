// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "vehicle_sensors.hpp"

#include <mujoco/mujoco.h>

#include <array>
#include <cstdio>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using tinyxml2::XMLElement;

// The centre of mass of `vehicle`'s subtree in the body's axes, from the model as it stands.
std::array<double, 3> CentreOfMass(tinyxml2::XMLDocument* doc, const std::string& label) {
  tinyxml2::XMLPrinter printer;
  doc->Print(&printer);
  mjModel* m = CompileModel(printer.CStr(), label);
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

}  // namespace

void AddImuAndSensors(tinyxml2::XMLDocument* doc, XMLElement* root, XMLElement* body,
                      const std::string& label, std::vector<std::string>* notes) {
  const std::array<double, 3> com = CentreOfMass(doc, label);
  char pos[128];
  std::snprintf(pos, sizeof(pos), "%.17g %.17g %.17g", com[0], com[1], com[2]);
  XMLElement* site = body->InsertNewChildElement("site");
  site->SetAttribute("name", "imu");
  site->SetAttribute("pos", pos);
  site->SetAttribute("quat", "1 0 0 0");
  site->SetAttribute("size", "0.005");
  site->SetAttribute("group", "5");  // not drawn by default
  notes->push_back(std::string("added site 'imu' at the centre of mass (") + pos +
                   " in body axes)");

  XMLElement* sensor = root->FirstChildElement("sensor");
  if (!sensor) sensor = root->InsertNewChildElement("sensor");
  const char* const kinds[][2] = {
      {"framepos", "pos"}, {"framelinvel", "vel"}, {"framequat", "quat"}};
  for (const auto& k : kinds) {
    XMLElement* s = sensor->InsertNewChildElement(k[0]);
    s->SetAttribute("name", k[1]);
    s->SetAttribute("objtype", "site");
    s->SetAttribute("objname", "imu");
  }
  XMLElement* gyro = sensor->InsertNewChildElement("gyro");
  gyro->SetAttribute("name", "gyro");
  gyro->SetAttribute("site", "imu");
  notes->push_back("added sensors pos, vel, quat, gyro at site 'imu'");
}

}  // namespace mjf::runner
