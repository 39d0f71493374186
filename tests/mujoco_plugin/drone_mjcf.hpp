// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A drone written as a MuJoCo user writes one, flown by mjformation.attitude (its instance
// 'autopilot' holds (0, 0, 1) m from a tilted, yawed start 0.4 m away): the tests of the
// attitude plugin vary its inertia, rotor arms and a gimbal; the attach tests attach copies of it.
#ifndef MJFORMATION_TESTS_MUJOCO_PLUGIN_DRONE_MJCF_HPP_
#define MJFORMATION_TESTS_MUJOCO_PLUGIN_DRONE_MJCF_HPP_

#include <string>

namespace mjf::testing {

// Our drone's inertia, as the body's own axes see it (kg m^2).
constexpr char kBodyAligned[] =
    R"(<inertial pos="0 0 0" mass="1.2" diaginertia="0.012 0.012 0.022"/>)";

// Where the rotor sites are: on the drone's body, or on a child body (a frame turned 90 degrees
// about z, the sites placed so that the body sees them where kOnBody puts them), fixed or moved
// by a hinge.
enum class Arms { kOnBody, kOnFrame, kOnHingedFrame };

struct DroneOptions {
  std::string inertial = kBodyAligned;  // the body's <inertial> element
  // A camera gimbal on a ball joint driven by an orientation actuator declared before the rotors.
  bool gimbal = false;
  Arms arms = Arms::kOnBody;
  const char* timestep = "0.002";  // s, <option timestep>
  // The body references the instance (<plugin instance="autopilot"/>), which MuJoCo needs to
  // carry the instance through an attach.
  bool body_references_instance = false;
};

inline std::string RotorSites(Arms arms) {
  if (arms == Arms::kOnBody) {
    return R"(<site name="s_front_right" pos="0.16 -0.16 0.03"/>
      <site name="s_back_left" pos="-0.16 0.16 0.03"/>
      <site name="s_front_left" pos="0.16 0.16 0.03"/>
      <site name="s_back_right" pos="-0.16 -0.16 0.03"/>)";
  }
  // Body (x, y) is frame (y, -x): the frame is turned +90 degrees about z.
  return std::string(R"(<body name="frame" euler="0 0 90">)") +
         (arms == Arms::kOnHingedFrame ? R"(<joint name="fold" type="hinge" axis="0 0 1"/>
        <geom type="sphere" size="0.01" mass="0.01" contype="0" conaffinity="0"/>)"
                                       : "") +
         R"(
        <site name="s_front_right" pos="-0.16 -0.16 0.03"/>
        <site name="s_back_left" pos="0.16 0.16 0.03"/>
        <site name="s_front_left" pos="0.16 -0.16 0.03"/>
        <site name="s_back_right" pos="-0.16 0.16 0.03"/>
      </body>)";
}

// The drone's MJCF (body 'quad', free joint 'root', rotors m_front_right .. m_back_right).
inline std::string DroneXml(const DroneOptions& o) {
  const std::string gimbal_body = o.gimbal ? R"(<body name="gimbal" pos="0 0 -0.05">
          <joint name="gimbal" type="ball" damping="0.001"/>
          <geom type="sphere" size="0.02" mass="0.02" contype="0" conaffinity="0"/>
        </body>)"
                                           : "";
  const std::string gimbal_actuator =
      o.gimbal ? R"(<orientation name="gimbal" joint="gimbal" kp="0.01" input="quat"/>)" : "";
  return R"(<mujoco model="drone">
  <extension>
    <plugin plugin="mjformation.attitude">
      <instance name="autopilot">
        <config key="body" value="quad"/>
        <config key="actuators" value="m_front_right m_back_left m_front_left m_back_right"/>
        <config key="attitude" value="plugin = 'geometric', tilt_max = 0.5"/>
        <config key="guidance" value="plugin = 'hover', position = '0 0 1'"/>
      </instance>
    </plugin>
  </extension>
  <option timestep=")" +
         std::string(o.timestep) + R"("/>
  <default>
    <default class="motor">
      <general dyntype="filter" dynprm="0.03" ctrllimited="true" ctrlrange="0 9"/>
    </default>
  </default>
  <worldbody>
    <body name="quad" pos="0.3 -0.2 0.8" euler="0.2 0.1 0.3">
      )" +
         (o.body_references_instance ? R"(<plugin instance="autopilot"/>)" : "") + R"(
      <freejoint name="root"/>
      )" +
         o.inertial +
         R"(
      <geom type="box" size="0.09 0.09 0.03" mass="0" contype="0" conaffinity="0"/>
      )" +
         RotorSites(o.arms) + gimbal_body +
         R"(
    </body>
  </worldbody>
  <actuator>
    )" + gimbal_actuator +
         R"(
    <general name="m_front_right" class="motor" site="s_front_right" gear="0 0 1 0 0 -0.02"/>
    <general name="m_back_left" class="motor" site="s_back_left" gear="0 0 1 0 0 -0.02"/>
    <general name="m_front_left" class="motor" site="s_front_left" gear="0 0 1 0 0 0.02"/>
    <general name="m_back_right" class="motor" site="s_back_right" gear="0 0 1 0 0 0.02"/>
  </actuator>
</mujoco>
)";
}

// The attitude tests' drone: `inertial` its <inertial> element, `gimbal` as DroneOptions says.
inline std::string DroneXml(const std::string& inertial, bool gimbal, Arms arms = Arms::kOnBody) {
  DroneOptions o;
  o.inertial = inertial;
  o.gimbal = gimbal;
  o.arms = arms;
  return DroneXml(o);
}

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_MUJOCO_PLUGIN_DRONE_MJCF_HPP_
