// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#ifndef MJFORMATION_PLUGINS_FORMATION_PLUGINS_HPP_
#define MJFORMATION_PLUGINS_FORMATION_PLUGINS_HPP_

#include <mjformation/plugin.h>

namespace mjf::formation::adapter {

extern const mjfPlugin kSmcContinuous;         // smc_continuous.cc: eq. (30) / (33)
extern const mjfPlugin kSmcDiscrete;           // smc_discrete.cc: eq. (48) / (53), zero-order hold
extern const mjfPlugin kConsensusLinear;       // consensus_linear.cc: linear baseline
extern const mjfPlugin kSmcDiscreteAgent;      // agent_plugins.cc: eq. (48), per follower
extern const mjfPlugin kSmcContinuousAgent;    // agent_plugins.cc: eq. (30), per follower
extern const mjfPlugin kConsensusLinearAgent;  // agent_plugins.cc: linear, per follower
// The laws from the literature (one file each, the maths in src/ of the same name):
extern const mjfPlugin kVsTracking;        // vs_tracking.cc: Cao & Ren, IEEE TAC 2012
extern const mjfPlugin kSuperTwisting;     // super_twisting.cc: Levant 1993 on s_i = K e_i
extern const mjfPlugin kAdaptiveTracking;  // adaptive_tracking.cc: Li, Liu, Ren & Xie, TAC 2013
extern const mjfPlugin kObserverTracking;  // observer_tracking.cc: Hong, Hu & Gao, Aut. 2006
extern const mjfPlugin kTerminalSmc;       // terminal_smc.cc: Feng, Yu & Man, Automatica 2002

}  // namespace mjf::formation::adapter

#endif  // MJFORMATION_PLUGINS_FORMATION_PLUGINS_HPP_
