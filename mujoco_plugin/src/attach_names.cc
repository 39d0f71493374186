// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "attach_names.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_set>

namespace mjf::native {
namespace {

std::vector<std::string> ReferencingBodies(const mjModel* m, int instance) {
  std::vector<std::string> out;
  for (int b = 1; b < m->nbody; ++b) {
    if (m->body_plugin[b] != instance) continue;
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    out.push_back(name ? name : "#" + std::to_string(b));
  }
  return out;
}

bool References(const mjModel* m, int instance, const std::string& body) {
  const int b = mj_name2id(m, mjOBJ_BODY, body.c_str());
  return b > 0 && m->body_plugin[b] == instance;
}

// Under `names`: the configured bodies that do not reference the instance, and the referencing
// bodies that are not configured ones. Both empty: the affixes are the instance's.
struct Mismatch {
  std::vector<std::string> missing, foreign;
  bool empty() const { return missing.empty() && foreign.empty(); }
};

Mismatch Compare(const mjModel* m, int instance, const std::vector<std::string>& bodies,
                 const std::vector<std::string>& referencing, const runner::SceneNames& names) {
  Mismatch out;
  std::unordered_set<std::string> expected;  // a set: an exported swarm may hold 10,000 vehicles
  for (const std::string& body : bodies) {
    const std::string name = names(body);
    if (!References(m, instance, name)) out.missing.push_back(name);
    expected.insert(name);
  }
  for (const std::string& body : referencing) {
    if (!expected.count(body)) out.foreign.push_back(body);
  }
  return out;
}

std::string Listed(const std::vector<std::string>& names) {
  std::string out;
  const size_t shown = std::min<size_t>(names.size(), 4);
  for (size_t i = 0; i < shown; ++i) out += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > shown) out += " and " + std::to_string(names.size() - shown) + " more";
  return out;
}

[[noreturn]] void Refuse(const std::string& where, const runner::SceneNames& names,
                         const Mismatch& mismatch) {
  std::string message = where + ": the bodies referencing it (<plugin instance=...> in a body) " +
                        "must be its vehicles' bodies, named '" + names.prefix + "<body>" +
                        names.suffix + "' after an attach";
  if (!mismatch.missing.empty()) {
    message += "; missing or not referencing it: " + Listed(mismatch.missing);
  }
  if (!mismatch.foreign.empty()) {
    message += "; referencing it but none of its vehicles: " + Listed(mismatch.foreign);
  }
  throw std::runtime_error(message +
                           ". Attach the exported scene's whole worldbody (one vehicle cannot "
                           "fly without its swarm's instance), and give each attached copy a "
                           "prefix of its own (an instance whose name is taken is not copied)");
}

}  // namespace

runner::SceneNames InstanceNames(const mjModel* m, int instance,
                                 const std::vector<std::string>& bodies, const std::string& where) {
  const std::vector<std::string> referencing = ReferencingBodies(m, instance);
  if (referencing.empty()) return {};
  // Every place a configured name sits in the first referencing body's name is a candidate
  // (prefix, suffix); the one under which the bodies match exactly is the attach's. Trying each
  // place, rather than the last, keeps a prefix that contains a body's own name right.
  const std::string& first = referencing.front();
  runner::SceneNames closest;
  Mismatch closest_mismatch;
  bool any = false;
  for (const std::string& body : bodies) {
    for (size_t at = first.find(body); at != std::string::npos; at = first.find(body, at + 1)) {
      const runner::SceneNames names{first.substr(0, at), first.substr(at + body.size())};
      const Mismatch mismatch = Compare(m, instance, bodies, referencing, names);
      if (mismatch.empty()) return names;
      if (!any) {
        closest = names;
        closest_mismatch = mismatch;
        any = true;
      }
    }
  }
  if (!any) closest_mismatch = Compare(m, instance, bodies, referencing, {});
  Refuse(where, closest, closest_mismatch);
}

}  // namespace mjf::native
