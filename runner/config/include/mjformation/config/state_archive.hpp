// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The runner's own state as bytes, for checkpoints (`run --checkpoint-every`, `--resume`) and
// the Python module's Simulation.get_state()/set_state(). One walk does both directions: a
// class lists what it carries from one step to the next once,
//
//   template <typename Archive>
//   void VisitState(Archive& a) { a(sums_, count_, events_, engine_); }
//
// and StateArchive writes it (Saving) or reads it back (Loading) in that order. Unlike the
// plugin ABI's fixed-size double arrays (mjformation/plugin_state.hpp), the runner's
// accumulators grow (safety events, trails), so containers carry their length. Numbers are
// stored as their bytes (exact); random engines as their textual state (exact, the standard's
// operator<<). A truncated or foreign archive throws StateArchiveError, never reads past the end.
#ifndef MJFORMATION_CONFIG_STATE_ARCHIVE_HPP_
#define MJFORMATION_CONFIG_STATE_ARCHIVE_HPP_

#include <array>
#include <complex>
#include <cstdint>
#include <cstring>
#include <deque>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace mjf::runner {

class StateArchiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a member is, for both archives' walks (this StateArchive and FixedStateArchive): they
// differ in how they store a kind, never in which kinds there are.
namespace state_kinds {

// A member the walk descends into: its type says what it carries (VisitState).
template <typename T, typename Archive, typename = void>
struct HasVisitStateFor : std::false_type {};
template <typename T, typename Archive>
struct HasVisitStateFor<
    T, Archive, std::void_t<decltype(std::declval<T&>().VisitState(std::declval<Archive&>()))>>
    : std::true_type {};
template <typename T, typename Archive>
inline constexpr bool kHasVisitState = HasVisitStateFor<T, Archive>::value;

template <typename T>
inline constexpr bool kIsEngine =
    std::is_same_v<T, std::mt19937> || std::is_same_v<T, std::mt19937_64> ||
    std::is_same_v<T, std::minstd_rand> || std::is_same_v<T, std::minstd_rand0>;

// The Mersenne twisters among them (FixedStateArchive walks their words twist by twist).
template <typename T>
inline constexpr bool kIsTwister =
    std::is_same_v<T, std::mt19937> || std::is_same_v<T, std::mt19937_64>;

template <typename T>
inline constexpr bool kIsSequence = false;
template <typename T, typename A>
inline constexpr bool kIsSequence<std::vector<T, A>> = true;
template <typename T, typename A>
inline constexpr bool kIsSequence<std::deque<T, A>> = true;

template <typename T>
inline constexpr bool kIsFixedArray = false;
template <typename T, size_t N>
inline constexpr bool kIsFixedArray<std::array<T, N>> = true;

// Doubles side by side (a block one copy can move).
template <typename T>
inline constexpr bool kIsDoubles = false;
template <typename A>
inline constexpr bool kIsDoubles<std::vector<double, A>> = true;
template <size_t N>
inline constexpr bool kIsDoubles<std::array<double, N>> = true;
template <size_t N>
inline constexpr bool kIsDoubles<double[N]> = true;

template <typename T>
inline constexpr bool kIsOrdered = false;
template <typename T, typename C, typename A>
inline constexpr bool kIsOrdered<std::set<T, C, A>> = true;

template <typename T>
inline constexpr bool kIsPairLike = false;
template <typename A, typename B>
inline constexpr bool kIsPairLike<std::pair<A, B>> = true;
template <typename... T>
inline constexpr bool kIsPairLike<std::tuple<T...>> = true;

}  // namespace state_kinds

// `bytes` as a message can quote them: printable ASCII as it is, every other byte as \xNN (a NUL
// would end the message where it is printed), and at most the first 48 bytes (a damaged length
// can make a label of the rest of the file).
inline std::string PrintableExcerpt(const std::string& bytes) {
  constexpr size_t kShown = 48;
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < bytes.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else {
      out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
    }
  }
  if (bytes.size() > kShown) out += "... (" + std::to_string(bytes.size()) + " bytes)";
  return out;
}

class StateArchive {
 public:
  // Saving: an empty archive that grows. Loading: reads `bytes` from the start.
  StateArchive() = default;
  explicit StateArchive(std::string bytes) : bytes_(std::move(bytes)), loading_(true) {}

  bool loading() const { return loading_; }
  const std::string& bytes() const { return bytes_; }
  // True when a loading archive was read to its end (a checkpoint holds nothing unread).
  bool at_end() const { return cursor_ == bytes_.size(); }

  template <typename T>
  void operator()(T& value) {
    Visit(value);
  }
  template <typename T, typename... Rest>
  void operator()(T& first, Rest&... rest) {
    Visit(first);
    (Visit(rest), ...);
  }

  // Raw bytes, both ways.
  void Bytes(void* data, size_t size) {
    if (!loading_) {
      bytes_.append(static_cast<const char*>(data), size);
      return;
    }
    if (size > bytes_.size() - cursor_) {
      throw StateArchiveError("the saved state ends early (" + std::to_string(bytes_.size()) +
                              " bytes): the file is truncated or not a state of this run");
    }
    std::memcpy(data, bytes_.data() + cursor_, size);
    cursor_ += size;
  }

  // A label written on save and checked on load: a state read by another layout fails here,
  // naming the part, instead of loading garbage.
  void Tag(const std::string& name) {
    std::string seen = name;
    Visit(seen);
    if (seen != name) {
      throw StateArchiveError("the saved state holds '" + PrintableExcerpt(seen) + "' where '" +
                              name +
                              "' was expected: it was written by another version or "
                              "configuration");
    }
  }

 private:
  // A length, checked on load against what is left (a corrupt length never allocates wildly).
  size_t Length(size_t n, size_t element_bytes) {
    uint64_t v = n;
    Bytes(&v, sizeof(v));
    if (loading_ && element_bytes > 0 && v > (bytes_.size() - cursor_) / element_bytes) {
      throw StateArchiveError("the saved state holds a length of " + std::to_string(v) +
                              " past its end: the file is corrupt");
    }
    return static_cast<size_t>(v);
  }

  template <typename Engine>
  void RandomEngine(Engine& engine) {
    std::string text;
    if (!loading_) {
      std::ostringstream out;
      out << engine;
      text = out.str();
    }
    Visit(text);
    if (loading_) {
      std::istringstream in(text);
      in >> engine;
      if (in.fail()) throw StateArchiveError("a random engine's saved state does not read back");
    }
  }

  template <typename Container>
  void Sequence(Container& c) {
    const size_t n = Length(c.size(), 1);
    if constexpr (std::is_default_constructible_v<typename Container::value_type>) {
      if (loading_) c.resize(n);
    } else if (n != c.size()) {
      // Stages built from the configuration (one sensor model per vehicle): their number is
      // fixed, never read from the archive.
      throw StateArchiveError("the saved state holds " + std::to_string(n) + " stages where " +
                              std::to_string(c.size()) + " were expected");
    }
    for (auto& element : c) Visit(element);
  }

  template <typename Set>
  void Ordered(Set& s) {
    const size_t n = Length(s.size(), 1);
    if (!loading_) {
      for (auto element : s) Visit(element);  // a copy: set elements are const
      return;
    }
    s.clear();
    for (size_t k = 0; k < n; ++k) {
      typename Set::value_type element{};
      Visit(element);
      s.insert(std::move(element));
    }
  }

  template <typename T>
  void Visit(T& value) {
    if constexpr (state_kinds::kHasVisitState<T, StateArchive>) {
      value.VisitState(*this);
    } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      Bytes(&value, sizeof(T));
    } else if constexpr (std::is_same_v<T, std::string>) {
      const size_t n = Length(value.size(), 1);
      if (loading_) value.resize(n);
      if (n > 0) Bytes(value.data(), n);
    } else if constexpr (state_kinds::kIsEngine<T>) {
      RandomEngine(value);
    } else if constexpr (std::is_array_v<T> || state_kinds::kIsFixedArray<T>) {
      for (auto& element : value) Visit(element);
    } else if constexpr (state_kinds::kIsSequence<T>) {
      Sequence(value);
    } else if constexpr (state_kinds::kIsOrdered<T>) {
      Ordered(value);
    } else if constexpr (state_kinds::kIsPairLike<T>) {
      std::apply([&](auto&... parts) { (Visit(parts), ...); }, value);
    } else if constexpr (std::is_trivially_copyable_v<T>) {
      // std::complex and the plugin ABI's plain structs (mjfVehicleState,
      // mjfSetpoint): doubles and integers only, stored as their bytes.
      Bytes(&value, sizeof(T));
    } else {
      static_assert(sizeof(T) == 0,
                    "this member cannot be saved: give its type a VisitState member or visit "
                    "its members one by one");
    }
  }

  std::string bytes_;
  bool loading_ = false;
  size_t cursor_ = 0;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONFIG_STATE_ARCHIVE_HPP_
