// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// Plugins that claim another ABI version (a future one, and ABI 3, the one before declared plugin
// state): the host must refuse each naming both versions.
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
                              nullptr,
                              nullptr,
                              nullptr,
                              nullptr};
// Only abi_version is read of a foreign descriptor, so the ABI-4 struct stands in for ABI 3's.
const mjfPlugin kPreviousAbi = {
    3u,      "previous_abi", MJF_KIND_GUIDANCE, "built for ABI 3", 0,       nullptr, 0,
    nullptr, nullptr,        nullptr,           nullptr,           nullptr, nullptr, nullptr,
    nullptr, nullptr};
const mjfPlugin* const kPlugins[] = {&kFutureAbi, &kPreviousAbi};
}  // namespace

extern "C" const mjfPlugin* const* mjf_plugin_entry(int* count) {
  *count = 2;
  return kPlugins;
}
