// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// terminal_smc: Feng, Yu & Man (Automatica 2002)'s nonsingular terminal sliding mode on the
// formation errors e_ip, e_iv of eq. (16) (the core's terminal_smc.hpp), evaluated every physics
// step. sliding = s_i = e_ip + e_iv^(p/q) / beta.
#include <cmath>
#include <mjformation/formation/terminal_smc.hpp>
#include <stdexcept>
#include <string>

#include "adapter.hpp"

namespace mjf::formation::adapter {
// The attributes and their reading, shared with terminal_smc_agent.cc.
const mjfAttribute kTerminalSmcAttributes[] = {
    {"beta", "1", "surface gain beta > 0 of s = e_p + e_v^(p/q) / beta (not tuned)"},
    {"p", "5", "odd integer p, q < p < 2q"},
    {"q", "3", "odd integer q"},
    {kKeyRho, "1.5",
     "switching gain rho = l + eta > 0, m/s^2, above a_i0 times the leader's "
     "acceleration bound"},
    {kKeySign, "sgn", "sign function: sgn (as published) or sat (boundary layer)"},
    {kKeyBoundaryLayer, "0.1", "boundary-layer width phi of sat (sign = sat only)"},
};
const int kTerminalSmcAttributeCount =
    static_cast<int>(sizeof(kTerminalSmcAttributes) / sizeof(kTerminalSmcAttributes[0]));

namespace {

int ParseOddExponent(const plugin::Attributes& attributes, const char* key) {
  const double value = attributes.Number(key);
  if (!(std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e6)) {
    throw std::invalid_argument(std::string("attribute '") + key +
                                "': a whole number is required (got '" + attributes.String(key) +
                                "')");
  }
  return static_cast<int>(value);
}

}  // namespace

formation::TerminalSmcParams ParseTerminalSmcParams(const plugin::Attributes& attributes) {
  formation::TerminalSmcParams params;
  params.beta = attributes.Number("beta");
  params.p = ParseOddExponent(attributes, "p");
  params.q = ParseOddExponent(attributes, "q");
  params.rho = attributes.Number(kKeyRho);
  params.sign = formation::ParseSignFunction(attributes.String(kKeySign));
  params.boundary_layer = attributes.Number(kKeyBoundaryLayer);
  return params;
}

namespace {

struct Instance : SwarmInstance<formation::TerminalSmc> {
  using Config = formation::TerminalSmcParams;
  static void Read(const plugin::Attributes& attributes, Config* params) {
    *params = ParseTerminalSmcParams(attributes);
  }
  using SwarmInstance::SwarmInstance;
};

void Report(void* instance, mjfReportFn emit, void* user) {
  emit(user, "norm_inv_lh", static_cast<const Instance*>(instance)->controller.norm_inv_lh());
}

}  // namespace

const mjfPlugin kTerminalSmc = SwarmPlugin<Instance>(
    "terminal_smc", "nonsingular terminal sliding mode, Feng, Yu & Man (Automatica 2002)",
    kTerminalSmcAttributes, &Report);

}  // namespace mjf::formation::adapter
