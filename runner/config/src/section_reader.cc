// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "section_reader.hpp"

#include <cmath>

namespace mjf::runner {
namespace {

thread_local AcceptedKeyMap* accepted_keys = nullptr;

}  // namespace

AcceptedKeysRecorder::AcceptedKeysRecorder(AcceptedKeyMap* into) { accepted_keys = into; }
AcceptedKeysRecorder::~AcceptedKeysRecorder() { accepted_keys = nullptr; }

void RecordAcceptedKeys(const std::string& section, const std::set<std::string>& keys) {
  if (accepted_keys) (*accepted_keys)[section].insert(keys.begin(), keys.end());
}

const char* TypeName(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

SourceLocation NodeLocation(const std::string& file, const toml::node* node,
                            const std::string& what) {
  if (!node) return {file, 0, what};
  // A table made for a --set (network.link=[...] makes [network]) has no source of its own: it is
  // where its first value came from.
  const toml::table* table = node->as_table();
  if (table && !table->empty() && node->source().begin.line == 0 && !node->source().path) {
    return NodeLocation(file, &table->cbegin()->second, what);
  }
  const auto& origin = node->source().path;
  if (origin && origin->rfind("--set ", 0) == 0) return {*origin, 0, what};
  return {file, static_cast<int>(node->source().begin.line), what};
}

void SectionReader::FailAt(const toml::node* node, const std::string& key,
                           const std::string& message) const {
  NodeLocation(path_, node ? node : table_, Where(key)).Fail(message);
}

double SectionReader::Number(const std::string& key, double fallback) {
  used_.insert(key);
  const toml::node* node = Node(key);
  return node ? AsNumber(*node, key) : fallback;
}

double SectionReader::AsNumber(const toml::node& node, const std::string& key) const {
  if (auto v = node.value_exact<double>()) {
    if (!std::isfinite(*v)) FailAt(&node, key, "expected a finite number");
    return *v;
  }
  if (auto v = node.value_exact<int64_t>()) return static_cast<double>(*v);
  FailAt(&node, key, std::string("expected a number, got ") + TypeName(node));
}

int64_t SectionReader::Integer(const std::string& key, int64_t fallback) {
  used_.insert(key);
  const toml::node* node = Node(key);
  if (!node) return fallback;
  if (auto v = node->value_exact<int64_t>()) return *v;
  Fail(key, std::string("expected an integer, got ") + TypeName(*node));
}

bool SectionReader::Bool(const std::string& key, bool fallback) {
  used_.insert(key);
  const toml::node* node = Node(key);
  if (!node) return fallback;
  if (auto v = node->value_exact<bool>()) return *v;
  Fail(key, std::string("expected true or false, got ") + TypeName(*node));
}

std::string SectionReader::String(const std::string& key, const std::string& fallback) {
  used_.insert(key);
  const toml::node* node = Node(key);
  if (!node) return fallback;
  if (auto v = node->value_exact<std::string>()) return *v;
  Fail(key, std::string("expected a string, got ") + TypeName(*node));
}

const toml::array* SectionReader::Array(const std::string& key) {
  used_.insert(key);
  const toml::node* node = Node(key);
  if (!node) return nullptr;
  if (const toml::array* a = node->as_array()) return a;
  Fail(key, std::string("expected an array, got ") + TypeName(*node));
}

std::vector<double> SectionReader::Numbers(const std::string& key, std::vector<double> fallback,
                                           int expected_size) {
  const toml::array* a = Array(key);
  if (!a) return fallback;
  std::vector<double> out;
  for (const toml::node& item : *a) out.push_back(AsNumber(item, key));
  if (expected_size >= 0 && static_cast<int>(out.size()) != expected_size) {
    Fail(key, "expected " + std::to_string(expected_size) + " numbers, got " +
                  std::to_string(out.size()));
  }
  return out;
}

std::array<double, 3> SectionReader::Vector3(const std::string& key,
                                             std::array<double, 3> fallback) {
  used_.insert(key);
  const toml::node* node = Node(key);
  if (!node) return fallback;
  const toml::array* a = node->as_array();
  if (!a || a->size() != 3) Fail(key, "expected [x, y, z]");
  return {AsNumber(*a->get(0), key), AsNumber(*a->get(1), key), AsNumber(*a->get(2), key)};
}

void SectionReader::RejectUnknown() const {
  RecordAcceptedKeys(reference_, used_);
  if (!table_) return;
  for (auto&& [key, node] : *table_) {
    const std::string k(key.str());
    if (used_.count(k)) continue;
    std::string known;
    for (const auto& u : used_) known += (known.empty() ? "" : ", ") + u;
    FailAt(&node, k, "unknown key (this section knows: " + known + ")");
  }
}

}  // namespace mjf::runner
