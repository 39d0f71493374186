// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A stage's state as a fixed number of doubles, for the control tick's state
// (ControlTick::GetState): the native MuJoCo plugin keeps it in plugin_state, whose length MuJoCo
// fixes when the model compiles, and the runner's checkpoints hold the same block. The walk is
// the one StateArchive takes (a class's `template <typename Archive> VisitState(Archive&)`), with
// two differences that keep the length fixed:
//   - a container's length is never stored: it is the one the stage was built with from the
//     configuration (a latency buffer, one sensor model per vehicle), and loading never resizes;
//   - a random engine is stored as its own words, not as text (whose length varies).
// The native plugin saves and loads the whole state at every step, and a Mersenne twister is
// most of it (313 64-bit words per stream; a scene with sensors holds dozens of streams). A
// twister rewrites all its state words together, once every state_size draws, and in between
// moves only its index; so its words in a block are identified by their first and last word
// (both are rewritten at every twist: equal in both means the same twist of the same stream,
// but for a chance of 2^-64 per word for a block of another stream). Loading skips the words of
// a twister whose block holds its own words (the native plugin's cache, loaded from the same
// block at the last step), and Updating, a Saving into a block that holds what this walk last
// saved or loaded, writes a twister's words only after a twist: the index alone otherwise.
// Every number goes in exactly: a double as itself; an integer of up to 32 bits as its value; a
// 64-bit integer and an engine's words as 32-bit halves, each an exact integer value, so the
// block holds no NaN pattern of our making and any copy of the doubles (mju_copy, numpy) keeps it.
// Three passes over the same walk: Sizing counts, Saving writes, Loading reads.
#ifndef MJFORMATION_CONFIG_FIXED_STATE_ARCHIVE_HPP_
#define MJFORMATION_CONFIG_FIXED_STATE_ARCHIVE_HPP_

#include <mjformation/plugin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <deque>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "mjformation/config/state_archive.hpp"

namespace mjf::runner {

class FixedStateArchive {
 public:
  static FixedStateArchive Sizing() { return FixedStateArchive(nullptr, nullptr); }
  static FixedStateArchive Saving(double* out) { return FixedStateArchive(out, nullptr); }
  static FixedStateArchive Loading(const double* in) { return FixedStateArchive(nullptr, in); }
  // Saving into a block that holds the state this walk's owner last saved or loaded (plugin_state
  // from one step to the next): what has not changed since is not written again.
  static FixedStateArchive Updating(double* block) {
    FixedStateArchive archive(block, nullptr);
    archive.updating_ = true;
    return archive;
  }

  bool loading() const { return in_ != nullptr; }
  // A Sizing walk: it neither reads nor writes a block.
  bool sizing() const { return in_ == nullptr && out_ == nullptr; }
  // Doubles walked so far (after a Sizing walk: the state's length).
  size_t size() const { return cursor_; }

  template <typename... T>
  void operator()(T&... values) {
    (Visit(values), ...);
  }

  // The unused slots of a bounded queue, after its used ones were walked: `count` slots of `size`
  // doubles, blank. Loading skips them (never read); Saving writes zeros; Updating writes zeros
  // over the first `were_used` of them only (slots the block used before this walk), the others
  // hold the zeros the last walk left.
  void UnusedSlots(size_t count, size_t size, size_t were_used) {
    if (out_) {
      const size_t zeroed = updating_ ? std::min(count, were_used) : count;
      std::fill(out_ + cursor_, out_ + cursor_ + zeroed * size, 0.0);
    }
    cursor_ += count * size;
  }
  // While updating, the whole number the block holds at the cursor (what the last walk wrote
  // there: a queue's length), else `otherwise`; also `otherwise` when the block holds no whole
  // number in [0, otherwise] there.
  size_t BlockCount(size_t otherwise) const {
    if (!updating_) return otherwise;
    const double value = out_[cursor_];
    if (!(value >= 0 && value <= static_cast<double>(otherwise)) ||
        static_cast<double>(static_cast<size_t>(value)) != value) {
      return otherwise;
    }
    return static_cast<size_t>(value);
  }

  // n doubles stored as themselves (as Visit stores a vector of them), of which only
  // [changed, changed + count) can differ from what the block holds while updating: only those
  // are written then. `count` past n: all of them.
  void DoublesChanged(double* values, size_t n, size_t changed, size_t count) {
    if (updating_ && count <= n && changed + count <= n) {
      std::memcpy(out_ + cursor_ + changed, values + changed, count * sizeof(double));
      cursor_ += n;
      return;
    }
    Doubles(values, n);
  }

  // n doubles that another walk writes or reads in place, with no copy between (a plugin's
  // declared state, ABI 4): save(double* out) while saving or updating, load(const double* in)
  // while loading, neither while sizing.
  template <typename Save, typename Load>
  void Block(size_t n, Save save, Load load) {
    if (out_) save(out_ + cursor_);
    if (in_) load(in_ + cursor_);
    cursor_ += n;
  }

 private:
  FixedStateArchive(double* out, const double* in) : out_(out), in_(in) {}

  void Slot(double& value) {
    if (out_) std::memcpy(out_ + cursor_, &value, sizeof(double));
    if (in_) std::memcpy(&value, in_ + cursor_, sizeof(double));
    ++cursor_;
  }
  // A 32-bit word as its value (exact in a double).
  void Word(uint32_t& word) {
    double value = word;
    Slot(value);
    if (in_) word = static_cast<uint32_t>(Whole(value, 0.0, 4294967295.0));
  }
  // A stored integer read back, checked first: converting a double outside the integer's range
  // is undefined, and a state written by hand or by another configuration may hold one. Every
  // range here is within 32 bits, so in range the truncation to int64_t is defined and gives the
  // value back exactly when it is whole (no libm floor: this runs for every word of an engine).
  double Whole(double value, double lowest, double highest) const {
    if (value >= lowest && value <= highest &&
        static_cast<double>(static_cast<int64_t>(value)) == value) {
      return value;
    }
    NotWhole(value);
  }
  [[noreturn]] void NotWhole(double value) const {
    throw StateArchiveError("the saved state holds " + std::to_string(value) + " at position " +
                            std::to_string(cursor_ - 1) +
                            " where an integer is stored: it was not written by this "
                            "configuration");
  }
  void Word64(uint64_t& word) {
    uint32_t high = static_cast<uint32_t>(word >> 32), low = static_cast<uint32_t>(word);
    Word(high);
    Word(low);
    if (in_) word = (static_cast<uint64_t>(high) << 32) | low;
  }
  // Bytes as 32-bit words. A random engine's words: the standard gives no access to its state
  // but text, so its object representation is copied (memcpy of its words, bit-exact; the
  // layout is this build's standard library's, as the block is this build's).
  // Word() for each, with the direction chosen once (an engine is hundreds of words, walked
  // both ways every native step).
  void Words(void* data, size_t bytes) {
    char* const at = static_cast<char*>(data);
    const size_t n = bytes / sizeof(uint32_t);
    for (size_t k = 0; out_ && k < n; ++k) {
      uint32_t word;
      std::memcpy(&word, at + k * sizeof(word), sizeof(word));
      out_[cursor_ + k] = word;
    }
    for (size_t k = 0; in_ && k < n; ++k) {
      ++cursor_;  // Whole names the position just read
      const uint32_t word = static_cast<uint32_t>(Whole(in_[cursor_ - 1], 0.0, 4294967295.0));
      std::memcpy(at + k * sizeof(word), &word, sizeof(word));
    }
    if (!in_) cursor_ += n;
  }
  // A Mersenne twister: its state words, then its index (libstdc++'s layout, as Words copies it).
  // Between twists only the index is walked when the block already holds the words (the file
  // comment).
  template <typename T>
  void Twister(T& engine) {
    using Word = typename T::result_type;
    static_assert(sizeof(T) == T::state_size * sizeof(Word) + sizeof(size_t),
                  "a twister stored as its state words then its index");
    constexpr size_t kWordHalves = sizeof(Word) / sizeof(uint32_t);
    constexpr size_t kStateHalves = T::state_size * kWordHalves;
    char* const at = reinterpret_cast<char*>(&engine);
    if ((in_ || updating_) && BlockHolds(at, kStateHalves, kWordHalves)) {
      cursor_ += kStateHalves;
      Words(at + kStateHalves * sizeof(uint32_t), sizeof(size_t));
      return;
    }
    Words(&engine, sizeof(T));
  }
  // Whether the block at the cursor holds these state words: its first and last word are theirs.
  bool BlockHolds(const char* words, size_t halves, size_t word_halves) const {
    const double* block = in_ ? in_ + cursor_ : out_ + cursor_;
    for (size_t k : {size_t{0}, halves - word_halves}) {
      for (size_t h = k; h < k + word_halves; ++h) {
        uint32_t half;
        std::memcpy(&half, words + h * sizeof(half), sizeof(half));
        if (block[h] != static_cast<double>(half)) return false;
      }
    }
    return true;
  }

  // Doubles stored as themselves, in one copy.
  void Doubles(double* values, size_t n) {
    if (out_) std::memcpy(out_ + cursor_, values, n * sizeof(double));
    if (in_) std::memcpy(values, in_ + cursor_, n * sizeof(double));
    cursor_ += n;
  }

  template <typename T>
  void Integer(T& value) {
    if constexpr (sizeof(T) <= sizeof(uint32_t)) {
      double v = static_cast<double>(value);
      Slot(v);
      if (in_) {
        value = static_cast<T>(Whole(v, static_cast<double>(std::numeric_limits<T>::min()),
                                     static_cast<double>(std::numeric_limits<T>::max())));
      }
    } else {
      static_assert(sizeof(T) == sizeof(uint64_t), "integers of up to 64 bits");
      uint64_t word = static_cast<uint64_t>(value);
      Word64(word);
      if (in_) value = static_cast<T>(word);
    }
  }

  template <typename T>
  void Visit(T& value) {
    if constexpr (state_kinds::kHasVisitState<T, FixedStateArchive>) {
      value.VisitState(*this);
    } else if constexpr (std::is_floating_point_v<T>) {
      double v = static_cast<double>(value);
      Slot(v);
      if (in_) value = static_cast<T>(v);
    } else if constexpr (std::is_same_v<T, bool>) {
      double v = value ? 1.0 : 0.0;
      Slot(v);
      if (in_) value = v != 0;
    } else if constexpr (std::is_integral_v<T>) {
      Integer(value);
    } else if constexpr (std::is_enum_v<T>) {
      auto underlying = static_cast<std::underlying_type_t<T>>(value);
      Integer(underlying);
      if (in_) value = static_cast<T>(underlying);
    } else if constexpr (state_kinds::kIsTwister<T>) {
      Twister(value);
    } else if constexpr (state_kinds::kIsEngine<T>) {
      static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % sizeof(uint32_t) == 0,
                    "an engine stored as its words");
      Words(&value, sizeof(T));
    } else if constexpr (state_kinds::kIsDoubles<T>) {
      Doubles(std::data(value), std::size(value));
    } else if constexpr (std::is_array_v<T> || state_kinds::kIsFixedArray<T> ||
                         state_kinds::kIsSequence<T>) {
      for (auto& element : value) Visit(element);
    } else if constexpr (state_kinds::kIsPairLike<T>) {
      std::apply([&](auto&... parts) { (Visit(parts), ...); }, value);
    } else if constexpr (std::is_same_v<T, mjfVehicleState>) {
      // The plugin ABI's plain structs field by field: their doubles as themselves (one copy
      // per array), their counters as integers. Walked for every vehicle at every native step.
      Visit(value.pos), Visit(value.vel), Visit(value.quat), Visit(value.gyro);
    } else if constexpr (std::is_same_v<T, mjfEstimate>) {
      Visit(value.state), Visit(value.covariance), Visit(value.rejected), Visit(value.fused);
    } else if constexpr (std::is_same_v<T, mjfMessage>) {
      // The same numbers in the same order as field by field, with send_time, the state and the
      // input (17 doubles side by side in the ABI's struct) in one copy: every link's messages
      // are walked at every native step.
      static_assert(offsetof(mjfMessage, input) + sizeof(value.input) ==
                        offsetof(mjfMessage, send_time) + kMessageDoubles * sizeof(double),
                    "mjfMessage: send_time, state and input side by side");
      Visit(value.sender), Visit(value.round);
      Doubles(&value.send_time, kMessageDoubles);
      Visit(value.n_payload), Visit(value.payload);
    } else if constexpr (std::is_trivially_copyable_v<T> && sizeof(T) % sizeof(uint32_t) == 0) {
      // Another plain struct without padding, as its words.
      Words(&value, sizeof(T));
    } else {
      static_assert(sizeof(T) == 0,
                    "this member has no fixed size: give its type a VisitState member or visit "
                    "its members one by one");
    }
  }

  // mjfMessage's doubles from send_time to the end of input: 1 + 13 (mjfVehicleState) + 3.
  static constexpr size_t kMessageDoubles = 1 + sizeof(mjfVehicleState) / sizeof(double) + 3;

  double* out_;
  const double* in_;
  bool updating_ = false;
  size_t cursor_ = 0;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_FIXED_STATE_ARCHIVE_HPP_
