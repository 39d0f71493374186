// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The network's state walked by a fixed-length archive (runner/config's FixedStateArchive, the
// control tick's state that the native MuJoCo plugin keeps in plugin_state and the runner's
// checkpoints hold): an Archive has operator()(values...) and loading(), and walks an
// mjfVehicleState field by field. A message is walked field by field (never as its bytes:
// mjfMessage has padding, whose bytes are nobody's), and a queue that grows and shrinks is
// walked as its length and a fixed number of slots.
#ifndef MJFORMATION_NETWORK_MESSAGE_STATE_HPP_
#define MJFORMATION_NETWORK_MESSAGE_STATE_HPP_

#include <mjformation/plugin.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mjf::network {

// Field by field: sender, round, send_time, state, input, n_payload, payload (the archive walks
// the struct in that order: FixedStateArchive, whose doubles of the state go as one copy).
template <typename Archive>
void VisitMessage(Archive& archive, mjfMessage& m) {
  archive(m);
}

template <typename Archive>
void VisitMessages(Archive& archive, std::vector<mjfMessage>& messages) {
  for (mjfMessage& m : messages) VisitMessage(archive, m);
}

// std::vector<bool> hands out proxies, not references: each flag as a bool of its own.
template <typename Archive>
void VisitFlags(Archive& archive, std::vector<bool>& flags) {
  for (size_t k = 0; k < flags.size(); ++k) {
    bool flag = flags[k];
    archive(flag);
    if (archive.loading()) flags[k] = flag;
  }
}

// An archive that walks a queue's unused slots in one call (FixedStateArchive::UnusedSlots).
template <typename Archive, typename = void>
struct WalksUnusedSlots : std::false_type {};
template <typename Archive>
struct WalksUnusedSlots<Archive, std::void_t<decltype(std::declval<Archive&>().UnusedSlots(
                                     size_t{}, size_t{}, size_t{}))>> : std::true_type {};

// A queue of at most `capacity` items (a bound the configuration fixes): its length, then
// `capacity` slots, the unused ones blank, so the walk has the same length whatever the queue
// holds. `what` names the queue when it holds more than the bound (a bound computed wrongly)
// or a saved length is past it (a state of another configuration). The native plugin walks
// every queue at every step, mostly empty: an archive that can walks the unused slots at once
// (never read when loading; zeros written only where the block held items before when
// updating).
template <typename Archive, typename T, typename VisitItem>
void VisitBounded(Archive& archive, std::vector<T>& items, size_t capacity, const char* what,
                  VisitItem visit_item) {
  size_t were_used = capacity;
  if constexpr (WalksUnusedSlots<Archive>::value) were_used = archive.BlockCount(capacity);
  uint32_t length = static_cast<uint32_t>(items.size());
  if (items.size() > capacity) {
    throw std::length_error(std::string(what) + " holds " + std::to_string(items.size()) +
                            " items, past the " + std::to_string(capacity) +
                            " its fixed-length state has room for");
  }
  archive(length);
  if (archive.loading()) {
    if (length > capacity) {
      throw std::length_error(std::string("the saved state's ") + what + " holds " +
                              std::to_string(length) +
                              " items where this configuration has room "
                              "for " +
                              std::to_string(capacity));
    }
    items.resize(length);
  }
  if constexpr (WalksUnusedSlots<Archive>::value) {
    for (T& item : items) visit_item(archive, item);
    Archive sizing = Archive::Sizing();
    T blank{};
    visit_item(sizing, blank);
    archive.UnusedSlots(capacity - items.size(), sizing.size(),
                        were_used > items.size() ? were_used - items.size() : 0);
  } else {
    for (size_t k = 0; k < capacity; ++k) {
      T blank{};
      visit_item(archive, k < items.size() ? items[k] : blank);
    }
  }
}

}  // namespace mjf::network

#endif  // MJFORMATION_NETWORK_MESSAGE_STATE_HPP_
