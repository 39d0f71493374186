// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The key reference (`mjformation keys`, docs/EXPERIMENT_FILE.md) lists exactly the keys the
// parser accepts, its defaults are values the parser takes, and the page in docs/ is current.
#include "mjformation/config/key_reference.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "mjformation/config/config.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using Document = std::map<std::string, std::map<std::string, std::string>>;

// A file with every section, so that every reader runs: [network] needs per-agent execution,
// [wind] a gust for the gust reader, a topology switch and a rotor fault for theirs,
// [[network.link]] one link of the graph.
Document EverySection() {
  return {
      {"run", {{"duration", "2.0"}}},
      {"vehicles",
       {{"followers", "2"},
        {"fault", "[{follower = 1, rotor = 0, at = 1.0, thrust_share = 0.5}]"}}},
      {"topology",
       {{"leader_links", "[1]"}, {"switch", "[{at = 1.0, edges = [[1, 2]], leader_links = [1]}]"}}},
      {"leader", {{"plugin", "\"hover\""}}},
      {"formation", {{"plugin", "\"hover\""}}},
      {"formation.shape", {{"type", "\"circle\""}}},
      {"attitude", {{"plugin", "\"pd_cascade\""}}},
      {"render", {}},
      {"sensors", {}},
      {"wind", {{"gusts", "[{start = 0.5, duration = 0.5, amplitude = [1.0, 0.0, 0.0]}]"}}},
      {"execution", {{"mode", "\"per_agent\""}}},
      {"network", {}},
      {"network.link", {{"from", "0"}, {"to", "1"}}},
      {"estimator", {{"plugin", "\"passthrough\""}}},
      {"safety", {}}};
}

std::string Toml(const Document& document) {
  std::string out;
  for (const auto& [section, keys] : document) {
    out += section == "network.link" ? "[[network.link]]\n" : "[" + section + "]\n";
    for (const auto& [key, value] : keys) out += key + " = " + value + "\n";
  }
  return out;
}

std::map<std::string, std::set<std::string>> ReferenceKeys() {
  std::map<std::string, std::set<std::string>> keys;
  for (const KeyEntry& e : ExperimentKeyReference()) keys[e.section].insert(e.key);
  return keys;
}

TEST(KeyReferenceTest, ListsExactlyTheKeysTheParserAccepts) {
  const auto accepted = AcceptedKeys(Toml(EverySection()), "every_section.toml");
  const auto reference = ReferenceKeys();
  for (const auto& [section, keys] : accepted) {
    for (const auto& key : keys) {
      EXPECT_TRUE(reference.count(section) && reference.at(section).count(key))
          << "[" << section << "] " << key
          << " is accepted by the parser but missing from the key reference "
             "(runner/config/src/key_reference.cc)";
    }
  }
  for (const auto& [section, keys] : reference) {
    for (const auto& key : keys) {
      EXPECT_TRUE(accepted.count(section) && accepted.at(section).count(key))
          << "[" << section << "] " << key << " is in the key reference but the parser refuses it";
    }
  }
}

TEST(KeyReferenceTest, EverySectionHasItsKeys) {
  const auto reference = ReferenceKeys();
  for (const char* section : kExperimentSections) {
    EXPECT_TRUE(reference.count(section)) << "[" << section << "] has no keys in the reference";
  }
}

// Every default the reference gives as a value is one the parser takes (its type and range),
// with what the key needs beside it.
TEST(KeyReferenceTest, DefaultsAreValuesTheParserTakes) {
  for (const KeyEntry& e : ExperimentKeyReference()) {
    if (e.default_toml.empty()) continue;
    Document document = EverySection();
    std::istringstream needs(e.needs);
    for (std::string line; std::getline(needs, line);) {
      const auto eq = line.find(" = ");
      document[e.section][line.substr(0, eq)] = line.substr(eq + 3);
    }
    document[e.section][e.key] = e.default_toml;
    if (e.section == "execution" && e.key == "mode" && e.default_toml != "\"per_agent\"") {
      document.erase("network");  // [network] needs per-agent execution
      document.erase("network.link");
    }
    if (e.section == "vehicles" && e.key == "followers") {
      document["topology"].erase("switch");  // its graph spans the file's two followers only
    }
    EXPECT_NO_THROW(ParseExperiment(Toml(document), "defaults.toml"))
        << "[" << e.section << "] " << e.key << " = " << e.default_toml;
  }
}

// Keys a reader reads only when they are present are still named when another key is unknown.
TEST(KeyReferenceTest, UnknownKeyMessageNamesKeysReadOnlyWhenPresent) {
  Document document = EverySection();
  document["vehicles"]["rotr"] = "1";
  try {
    ParseExperiment(Toml(document), "typo.toml");
    FAIL() << "an unknown key was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(),
                ::testing::AllOf(::testing::HasSubstr("thrust"), ::testing::HasSubstr("moments")));
  }
  document = EverySection();
  document["sensors"]["imuu"] = "1";
  try {
    ParseExperiment(Toml(document), "typo.toml");
    FAIL() << "an unknown key was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("imu,"));
  }
}

// docs/EXPERIMENT_FILE.md is `mjformation keys`' output: regenerate it with
// build/runner/mjformation keys > docs/EXPERIMENT_FILE.md
TEST(KeyReferenceTest, DocumentIsCurrent) {
  std::ifstream in(std::string(MJF_SOURCE_DIR) + "/docs/EXPERIMENT_FILE.md");
  const std::string document((std::istreambuf_iterator<char>(in)), {});
  ::testing::internal::CaptureStdout();
  const int code = mjf::testing::Cli({"keys"});
  const std::string printed = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(code, 0);
  EXPECT_EQ(printed, KeyReferenceMarkdown());
  EXPECT_TRUE(printed == document)
      << "docs/EXPERIMENT_FILE.md is stale: build/runner/mjformation keys > "
         "docs/EXPERIMENT_FILE.md";
}

TEST(KeyReferenceTest, PluginKeysTakeTheirArticle) {
  const std::string all = KeyReferenceMarkdown();
  EXPECT_THAT(all, ::testing::HasSubstr("| an attitude plugin |"));
  EXPECT_THAT(all, ::testing::HasSubstr("| an estimator plugin |"));
  EXPECT_THAT(all, ::testing::HasSubstr("| a guidance plugin |"));
  EXPECT_THAT(all, ::testing::Not(::testing::HasSubstr("| a attitude")));
}

TEST(KeyReferenceTest, OneSectionAndItsSubTables) {
  const std::string formation = KeyReferenceMarkdown("formation");
  EXPECT_THAT(formation, ::testing::HasSubstr("## [formation.shape]"));
  EXPECT_THAT(formation, ::testing::Not(::testing::HasSubstr("## [run]")));
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(mjf::testing::Cli({"keys", "formatoin"}), 1);
  EXPECT_THAT(::testing::internal::GetCapturedStderr(),
              ::testing::HasSubstr("unknown section 'formatoin'"));
}

}  // namespace
}  // namespace mjf::runner
