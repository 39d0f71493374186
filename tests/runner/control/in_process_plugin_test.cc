// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// In-process plugins (RegisterInProcessPlugin): listed by every registry created afterwards,
// after the search path's libraries, with the same ABI and duplicate-name checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "mjformation/control/plugin_host.hpp"

namespace mjf::runner {
namespace {

void* CreateNothing(const mjfCreateContext*) { return nullptr; }
int ComputeNothing(void*, const mjfStepContext*) { return 0; }

mjfPlugin Descriptor(const char* name, uint32_t abi) {
  return {abi,     name,    MJF_KIND_GUIDANCE, "test",          0,       nullptr,
          0,       nullptr, &CreateNothing,    &ComputeNothing, nullptr, nullptr,
          nullptr, nullptr, nullptr,           nullptr};
}

const mjfPlugin kGood = Descriptor("in_process_test", MJF_ABI_VERSION);
const mjfPlugin kForeignAbi = Descriptor("in_process_foreign", MJF_ABI_VERSION + 7);
const mjfPlugin kShadowed = Descriptor("circle", MJF_ABI_VERSION);  // a library's name

bool Mentions(const std::vector<std::string>& problems, const std::string& text) {
  return std::any_of(problems.begin(), problems.end(),
                     [&](const std::string& p) { return p.find(text) != std::string::npos; });
}

TEST(InProcessPlugin, IsFoundWithItsOriginAfterTheLibraries) {
  // Given three in-process descriptors registered (once each, however often)
  for (int k = 0; k < 2; ++k) {
    RegisterInProcessPlugin(&kGood, "in-process (test)");
    RegisterInProcessPlugin(&kForeignAbi, "in-process (test)");
    RegisterInProcessPlugin(&kShadowed, "in-process (test)");
  }
  // When a registry is created on the build tree's plugins
  PluginRegistry registry({MJF_BINARY_DIR "/plugins"});
  // Then the good one is found, named by its origin, listed once and last
  const LoadedPlugin& found = registry.Find("in_process_test", "test");
  EXPECT_EQ(found.descriptor, &kGood);
  EXPECT_EQ(found.library, "in-process (test)");
  EXPECT_EQ(registry.plugins().back().descriptor, &kGood);
  EXPECT_EQ(std::count_if(registry.plugins().begin(), registry.plugins().end(),
                          [](const LoadedPlugin& p) { return p.descriptor == &kGood; }),
            1);
  // the foreign-ABI one is refused, the one named like a library plugin is shadowed by it
  EXPECT_THROW(registry.Find("in_process_foreign", "test"), PluginError);
  EXPECT_TRUE(Mentions(registry.problems(), "'in_process_foreign' was built for plugin ABI " +
                                                std::to_string(MJF_ABI_VERSION + 7) +
                                                ", this runner speaks ABI " +
                                                std::to_string(MJF_ABI_VERSION)));
  EXPECT_NE(registry.Find("circle", "test").descriptor, &kShadowed);
  EXPECT_TRUE(Mentions(registry.problems(), "'circle' shadowed by a library"));
}

}  // namespace
}  // namespace mjf::runner
