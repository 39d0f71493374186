// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A formation law written in Python, flown through the runner as an in-process formation
// plugin: two descriptors ("python": one instance per swarm; "python_agent": one per follower,
// per-agent execution) whose compute() holds the GIL only while it calls the Python callable.
// The plugin ABI is unchanged: the runner sees an ordinary formation plugin.
#ifndef MJFORMATION_PYTHON_PYTHON_LAW_HPP_
#define MJFORMATION_PYTHON_PYTHON_LAW_HPP_

#include <mjformation/plugin.h>

namespace mjf::python {

// The descriptors; registered with the runner (RegisterInProcessPlugin) at import.
const mjfPlugin& CentralLawPlugin();
const mjfPlugin& AgentLawPlugin();

}  // namespace mjf::python

#endif  // MJFORMATION_PYTHON_PYTHON_LAW_HPP_
