// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// A plugin that claims another ABI version: the host must refuse it by name.
#include <mjformation/plugin.h>

namespace {
const mjfPlugin kFutureAbi = {99u,
                              "future_abi",
                              MJF_KIND_GUIDANCE,
                              "built for ABI 99",
                              0,
                              nullptr,
                              0,
                              nullptr,
                              nullptr,
                              nullptr,
                              nullptr,
                              nullptr,
                              nullptr};
const mjfPlugin* const kPlugins[] = {&kFutureAbi};
}  // namespace

extern "C" const mjfPlugin* const* mjf_plugin_entry(int* count) {
  *count = 1;
  return kPlugins;
}
