// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/control/src/plugin_host.cc: finding plugin libraries, refusing another ABI by naming both
// versions, the unknown-plugin message, attribute checking, and the instance life cycle.
#include "mjformation/control/plugin_host.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "error_of.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

const std::string kTestPlugins = MJF_TEST_PLUGIN_DIR;

std::string ErrorOf(const std::function<void()>& f) {
  return mjf::testing::ErrorOf<PluginError>(f, "(nothing thrown)");
}

bool AnyContains(const std::vector<std::string>& list, const std::string& part) {
  return std::any_of(list.begin(), list.end(),
                     [&](const std::string& s) { return s.find(part) != std::string::npos; });
}

TEST(PluginHostTest, KindNames) {
  EXPECT_STREQ(KindName(MJF_KIND_GUIDANCE), "guidance");
  EXPECT_STREQ(KindName(MJF_KIND_FORMATION), "formation");
  EXPECT_STREQ(KindName(MJF_KIND_ATTITUDE), "attitude");
  EXPECT_STREQ(KindName(MJF_KIND_FORMATION_AGENT), "per-agent formation");
  EXPECT_STREQ(KindName(MJF_KIND_ESTIMATOR), "estimator");
}

TEST(PluginHostTest, LoadsTheTestLibrariesAndNotesTheForeignAbi) {
  PluginRegistry registry({kTestPlugins});
  const LoadedPlugin& p = registry.Find("test_required", "here");
  EXPECT_STREQ(p.descriptor->name, "test_required");
  EXPECT_EQ(p.descriptor->kind, MJF_KIND_GUIDANCE);
  EXPECT_EQ(p.library, kTestPlugins + "/libmjf_test_plugins.so");
  // The ABI-99 descriptor is not loaded, and the problem names both versions.
  for (const auto& q : registry.plugins()) EXPECT_STRNE(q.descriptor->name, "future_abi");
  EXPECT_TRUE(
      AnyContains(registry.problems(), kTestPlugins +
                                           "/libmjf_test_badabi.so: plugin #0 was built for plugin "
                                           "ABI 99, this runner speaks ABI " +
                                           std::to_string(MJF_ABI_VERSION)));
  EXPECT_EQ(registry.search_path(), std::vector<std::string>{kTestPlugins});
}

TEST(PluginHostTest, AWrongAbiPluginIsRefusedNamingBothVersions) {
  PluginRegistry registry({kTestPlugins});
  EXPECT_THAT(ErrorOf([&] { registry.Find("future_abi", "exp.toml:4: [leader]"); }),
              AllOf(HasSubstr("exp.toml:4: [leader]: unknown plugin 'future_abi'"),
                    HasSubstr("built for plugin ABI 99"),
                    HasSubstr("this runner speaks ABI " + std::to_string(MJF_ABI_VERSION)),
                    HasSubstr("libmjf_test_badabi.so")));
}

// ABI 4 added declared plugin state: a library built against ABI 3 is refused, naming 3 and 4
// and where the migration is written.
TEST(PluginHostTest, AnAbi3PluginIsRefusedNamingBothVersionsAndTheMigration) {
  ASSERT_EQ(MJF_ABI_VERSION, 4u);
  PluginRegistry registry({kTestPlugins});
  EXPECT_THAT(ErrorOf([&] { registry.Find("previous_abi", "exp.toml:4: [leader]"); }),
              AllOf(HasSubstr("unknown plugin 'previous_abi'"),
                    HasSubstr("plugin #1 was built for plugin ABI 3, this runner speaks ABI 4"),
                    HasSubstr("docs/PLUGINS.md, \"Migrating from ABI 3\"")));
}

TEST(PluginHostTest, AnUnknownPluginListsTheValidNamesWithTheirKindsAndTheFolders) {
  const std::string absent = TempDir("ph_absent") + "/not_there";
  PluginRegistry registry({absent, kTestPlugins});  // an absent folder is not an error
  const std::string message = ErrorOf([&] { registry.Find("nope", "e.toml:9: [formation]"); });
  EXPECT_THAT(message, AllOf(HasSubstr("e.toml:9: [formation]: unknown plugin 'nope'; available: "),
                             HasSubstr("test_required (guidance)"),
                             HasSubstr("searched: " + absent + ", " + kTestPlugins)));
  // Every plugin found is listed.
  for (const auto& p : registry.plugins()) EXPECT_THAT(message, HasSubstr(p.descriptor->name));
}

TEST(PluginHostTest, AMisspeltPluginNameGetsTheNearestName) {
  PluginRegistry registry({kTestPlugins});
  EXPECT_THAT(ErrorOf([&] { registry.Find("test_requierd", "e.toml:9: [leader]"); }),
              HasSubstr("e.toml:9: [leader]: unknown plugin 'test_requierd'; did you mean "
                        "'test_required'?; available: "));
}

// In-process plugins are the process's (RegisterInProcessPlugin): a test of this binary that
// registered one before, when the tests run in one process, leaves it listed. An empty folder
// gives no plugin of its own either way.
TEST(PluginHostTest, NoPluginsAtAll) {
  const std::string empty = TempDir("ph_empty");
  PluginRegistry registry({empty});
  size_t in_process = 0;
  for (const auto& p : registry.plugins()) in_process += p.library.rfind("in-process", 0) == 0;
  EXPECT_EQ(registry.plugins().size(), in_process);
  EXPECT_TRUE(registry.problems().empty());
  const std::string error = ErrorOf([&] { registry.Find("hover", "w"); });
  EXPECT_THAT(error, HasSubstr("w: unknown plugin 'hover'"));
  EXPECT_THAT(error, HasSubstr("searched: " + empty));
  if (in_process == 0) {
    EXPECT_THAT(error, HasSubstr("; no plugins found; "));
  }
}

TEST(PluginHostTest, ALibraryThatCannotBeLoadedIsAProblemNotAFailure) {
  const std::string dir = TempDir("ph_junk");
  WriteFile(dir + "/libjunk.so", "this is not an ELF file");
  WriteFile(dir + "/notalib.txt", "ignored: not lib*.so");
  PluginRegistry registry({dir, kTestPlugins});
  EXPECT_TRUE(AnyContains(registry.problems(), dir + "/libjunk.so: cannot load: "));
  EXPECT_FALSE(AnyContains(registry.problems(), "notalib"));
  EXPECT_NO_THROW(registry.Find("test_required", "w"));
}

TEST(PluginHostTest, FirstFolderWinsOnDuplicates) {
  namespace fs = std::filesystem;
  // The same library file name later on the path: skipped without a word.
  const std::string same_name = TempDir("ph_same");
  fs::copy_file(kTestPlugins + "/libmjf_test_plugins.so", same_name + "/libmjf_test_plugins.so");
  {
    PluginRegistry registry({same_name, kTestPlugins});
    EXPECT_EQ(registry.Find("test_required", "w").library, same_name + "/libmjf_test_plugins.so");
    EXPECT_FALSE(AnyContains(registry.problems(), "shadowed"));
  }
  // Another library defining the same plugin name: shadowed, and said so.
  const std::string other_name = TempDir("ph_shadow");
  fs::copy_file(kTestPlugins + "/libmjf_test_plugins.so", other_name + "/libshadow.so");
  PluginRegistry registry({kTestPlugins, other_name});
  EXPECT_EQ(registry.Find("test_required", "w").library, kTestPlugins + "/libmjf_test_plugins.so");
  EXPECT_TRUE(AnyContains(registry.problems(),
                          other_name + "/libshadow.so: plugin 'test_required' shadowed by one "
                                       "earlier on the search path"));
}

// A plugin defined here, so that every path of ResolveAttributes and PluginInstance is reached
// without a library.
struct Counters {
  int created = 0, reset = 0, destroyed = 0;
  std::vector<std::pair<std::string, std::string>> seen;  // what create() was handed
};
Counters g_counters;

const mjfAttribute kAttributes[] = {{"gain", "2.0", "a number"},
                                    {"period", nullptr, "s: sample period"},
                                    {"mode", "fast", "fast or slow"}};

void* LocalCreate(const mjfCreateContext* ctx) {
  g_counters.seen.clear();
  for (int i = 0; i < ctx->n_attributes; ++i)
    g_counters.seen.emplace_back(ctx->keys[i], ctx->values[i]);
  for (const auto& [k, v] : g_counters.seen) {
    if (k == "mode" && v != "fast" && v != "slow") {
      std::snprintf(ctx->error, ctx->error_size, "mode must be fast or slow, not '%s'", v.c_str());
      return nullptr;
    }
    if (k == "gain" && v == "0") return nullptr;  // no reason given
  }
  ++g_counters.created;
  return &g_counters;
}
int LocalCompute(void*, const mjfStepContext* ctx) { return ctx->step == 3 ? 7 : 0; }
void LocalReset(void*) { ++g_counters.reset; }
void LocalDestroy(void*) { ++g_counters.destroyed; }
void LocalReport(void*, mjfReportFn emit, void* user) {
  emit(user, "delta", 0.25);
  emit(user, "error_bound", 1.5);
}

const mjfPlugin kLocal = {MJF_ABI_VERSION,
                          "local",
                          MJF_KIND_FORMATION,
                          "test",
                          3,
                          kAttributes,
                          0,
                          nullptr,
                          LocalCreate,
                          LocalCompute,
                          LocalReset,
                          LocalDestroy,
                          LocalReport,
                          nullptr,
                          nullptr,
                          nullptr};

PluginSection Section(std::map<std::string, AttributeValue> attributes) {
  PluginSection s;
  s.section = "formation";
  s.plugin = "local";
  s.line = 7;
  s.attributes = std::move(attributes);
  return s;
}

TEST(PluginHostTest, AttributesInDeclarationOrderWithDefaults) {
  const auto resolved =
      ResolveAttributes(kLocal, Section({{"period", {"0.05", 9, ""}}}), "exp.toml");
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"gain", "2.0"}, {"period", "0.05"}, {"mode", "fast"}};
  EXPECT_EQ(resolved, expected);
}

TEST(PluginHostTest, UnknownAndMissingAttributesAreNamedWithFileLineAndSection) {
  EXPECT_EQ(ErrorOf([] {
              ResolveAttributes(kLocal,
                                Section({{"period", {"1", 9, ""}}, {"rho", {"0.1", 11, ""}}}),
                                "exp.toml");
            }),
            "exp.toml:11: [formation] rho: plugin 'local' has no attribute 'rho' (its "
            "attributes: gain, period, mode)");
  EXPECT_EQ(ErrorOf([] {
              ResolveAttributes(kLocal, Section({{"gain", {"3", 8, ""}}}), "exp.toml");
            }),
            "exp.toml:7: [formation] period: plugin 'local' requires attribute 'period' (s: "
            "sample period)");
  // Without a line (a section made in code) the location is the file alone.
  PluginSection no_line = Section({});
  no_line.line = 0;
  EXPECT_THAT(ErrorOf([&] { ResolveAttributes(kLocal, no_line, "exp.toml"); }),
              HasSubstr("exp.toml: [formation] period: "));
}

TEST(PluginHostTest, InstanceLifeCycle) {
  g_counters = {};
  const LoadedPlugin loaded{&kLocal, "inline.so"};
  {
    PluginInstance instance(loaded,
                            Section({{"period", {"0.05", 9, ""}}, {"mode", {"slow", 10, ""}}}),
                            "exp.toml", mjfCreateContext{});
    EXPECT_EQ(g_counters.created, 1);
    // create() was handed every declared key in declaration order, defaults filled in.
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"gain", "2.0"}, {"period", "0.05"}, {"mode", "slow"}};
    EXPECT_EQ(g_counters.seen, expected);
    EXPECT_EQ(instance.attributes(), expected);
    EXPECT_STREQ(instance.descriptor().name, "local");
    const std::vector<std::pair<std::string, double>> report = {{"delta", 0.25},
                                                                {"error_bound", 1.5}};
    EXPECT_EQ(instance.Report(), report);
    mjfStepContext ctx{};
    ctx.step = 2;
    EXPECT_EQ(instance.Compute(ctx), 0);
    ctx.step = 3;
    EXPECT_EQ(instance.Compute(ctx), 7);
    instance.Reset();
    EXPECT_EQ(g_counters.reset, 1);
    EXPECT_EQ(g_counters.destroyed, 0);
  }
  EXPECT_EQ(g_counters.destroyed, 1);
}

TEST(PluginHostTest, ARefusedConfigurationNamesPluginLibraryAndReason) {
  g_counters = {};
  const LoadedPlugin loaded{&kLocal, "inline.so"};
  EXPECT_EQ(ErrorOf([&] {
              PluginInstance p(loaded,
                               Section({{"period", {"1", 9, ""}}, {"mode", {"warp", 10, ""}}}),
                               "exp.toml", mjfCreateContext{});
            }),
            "exp.toml:7: [formation] plugin 'local' (inline.so) refused its configuration: mode "
            "must be fast or slow, not 'warp'");
  EXPECT_THAT(ErrorOf([&] {
                PluginInstance p(loaded,
                                 Section({{"period", {"1", 9, ""}}, {"gain", {"0", 8, ""}}}),
                                 "exp.toml", mjfCreateContext{});
              }),
              HasSubstr("refused its configuration: no reason given"));
  // Nothing was created, so nothing is destroyed.
  EXPECT_EQ(g_counters.destroyed, 0);
}

}  // namespace
}  // namespace mjf::runner
