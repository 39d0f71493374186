// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Plugin state (ABI 4) for C++ plugins in one member. A controller lists what it carries from
// one compute() to the next:
//
//   template <typename Visit>
//   void VisitState(Visit& visit) {
//     visit(integral_z_);         // a double
//     visit(has_sample_);         // bool, int, int64_t, size_t, an enum: stored exactly
//     visit(held_);               // std::vector / std::array / Eigen matrix / C array, of any
//                                 // of these, its size fixed at create()
//     inner_.VisitState(visit);   // or visit(inner_): a member with a VisitState of its own
//     for (Item& item : used_) visit(item);    // a table of at most kMax items: the rest
//     visit.Unused(kMax - used_.size(), blank);  // as slots of a blank item (all zeros)
//   }
//
// and StateSize / GetState / SetState (below) count, write and read exactly those numbers, in
// that order; StateSizeOf / GetStateOf / SetStateOf are the three mjfPlugin callbacks. A
// random engine of <random> is visited whole (its textual state, every word exact); a law
// that draws from a counter (the stock guidance laws) visits the counter.
//
// Not state: what compute() writes before it reads it (input buffers, scratch of a solve) and
// what create() fixes (gains, factorizations). A member left out is a member a copy or a
// checkpoint silently loses: list it when in doubt.
#ifndef MJFORMATION_PLUGIN_STATE_HPP_
#define MJFORMATION_PLUGIN_STATE_HPP_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <type_traits>
#include <utility>

namespace mjf::plugin {

enum class StateOp { kCount, kSave, kLoad };

template <StateOp Op>
class StateVisitor;

namespace state_detail {

template <typename T, typename Visitor, typename = void>
struct HasVisitState : std::false_type {};
template <typename T, typename Visitor>
struct HasVisitState<T, Visitor,
                     std::void_t<decltype(std::declval<T&>().VisitState(std::declval<Visitor&>()))>>
    : std::true_type {};

template <typename T, typename = void>
struct IsContiguous : std::false_type {};
template <typename T>
struct IsContiguous<
    T, std::void_t<decltype(*std::declval<T&>().data()), decltype(std::declval<T&>().size())>>
    : std::true_type {};

template <typename T>
struct IsRandomEngine : std::false_type {};
template <typename U, size_t w, size_t n, size_t m, size_t r, U a, size_t u, U d, size_t s, U b,
          size_t t, U c, size_t l, U f>
struct IsRandomEngine<std::mersenne_twister_engine<U, w, n, m, r, a, u, d, s, b, t, c, l, f>>
    : std::true_type {};
template <typename U, U a, U c, U m>
struct IsRandomEngine<std::linear_congruential_engine<U, a, c, m>> : std::true_type {};
template <typename U, size_t w, size_t s, size_t r>
struct IsRandomEngine<std::subtract_with_carry_engine<U, w, s, r>> : std::true_type {};

// The number of words in an engine's textual state (fixed by its type).
template <typename Engine>
size_t EngineWords() {
  static const size_t words = [] {
    std::ostringstream out;
    out << Engine();
    std::istringstream in(out.str());
    size_t n = 0;
    for (unsigned long long word; in >> word;) ++n;
    return n;
  }();
  return words;
}

}  // namespace state_detail

// True when T lists its state (a VisitState member template).
template <typename T>
inline constexpr bool kHasVisitState =
    state_detail::HasVisitState<T, StateVisitor<StateOp::kCount>>::value;

// Walks a VisitState: counts (kCount), writes to an array (kSave) or reads it back (kLoad).
template <StateOp Op>
class StateVisitor {
 public:
  StateVisitor() = default;
  explicit StateVisitor(double* cursor) : cursor_(cursor) {}

  template <typename T>
  void operator()(T& value) {
    Visit(value);
  }
  template <typename T, typename... Rest>
  void operator()(T& first, Rest&... rest) {
    Visit(first);
    (Visit(rest), ...);
  }
  size_t count() const { return count_; }

  // `slots` unused slots of a table of fixed size, each as many numbers as `blank` lists (an item
  // whose numbers are all zero): written as zeros, skipped when read back (a blank slot has
  // nothing to restore; the host walks the state at every step, so the usually empty part of a
  // table costs no copy in).
  template <typename T>
  void Unused(size_t slots, T& blank) {
    StateVisitor<StateOp::kCount> sizing;
    sizing(blank);
    const size_t n = slots * sizing.count();
    count_ += n;
    if constexpr (Op == StateOp::kSave) std::fill(cursor_, cursor_ + n, 0.0);
    if constexpr (Op != StateOp::kCount) cursor_ += n;
  }

 private:
  void Number(double& v) {
    ++count_;
    if constexpr (Op == StateOp::kSave) *cursor_++ = v;
    if constexpr (Op == StateOp::kLoad) v = *cursor_++;
  }

  // n doubles side by side, as n Number() calls would walk them.
  void Doubles(double* data, size_t n) {
    count_ += n;
    if constexpr (Op == StateOp::kSave) std::memcpy(cursor_, data, n * sizeof(double));
    if constexpr (Op == StateOp::kLoad) std::memcpy(data, cursor_, n * sizeof(double));
    if constexpr (Op != StateOp::kCount) cursor_ += n;
  }

  // A 64-bit integer as its two 32-bit halves (each exact in a double).
  template <typename T>
  void Wide(T& value) {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    double high = static_cast<double>(bits >> 32), low = static_cast<double>(bits & 0xffffffffu);
    Number(high);
    Number(low);
    if constexpr (Op == StateOp::kLoad) {
      bits = (static_cast<uint64_t>(high) << 32) | static_cast<uint64_t>(low);
      std::memcpy(&value, &bits, sizeof(bits));
    }
  }

  template <typename T>
  void Integer(T& value) {
    if constexpr (sizeof(T) > 4) {
      Wide(value);
    } else {
      double v = static_cast<double>(value);
      Number(v);
      if constexpr (Op == StateOp::kLoad) value = static_cast<T>(v);
    }
  }

  template <typename Engine>
  void RandomEngine(Engine& engine) {
    const size_t words = state_detail::EngineWords<Engine>();
    unsigned long long word = 0;
    if constexpr (Op == StateOp::kCount) {
      for (size_t k = 0; k < words; ++k) Wide(word);
    } else if constexpr (Op == StateOp::kSave) {
      std::ostringstream out;
      out << engine;
      std::istringstream in(out.str());
      for (size_t k = 0; k < words; ++k) {
        in >> word;
        Wide(word);
      }
    } else {
      std::ostringstream text;
      for (size_t k = 0; k < words; ++k) {
        Wide(word);
        text << (k ? " " : "") << word;
      }
      std::istringstream in(text.str());
      in >> engine;
    }
  }

  template <typename T>
  void Visit(T& value) {
    if constexpr (state_detail::HasVisitState<T, StateVisitor>::value) {
      value.VisitState(*this);
    } else if constexpr (std::is_same_v<T, double>) {
      Number(value);
    } else if constexpr (std::is_floating_point_v<T>) {
      double v = static_cast<double>(value);
      Number(v);
      if constexpr (Op == StateOp::kLoad) value = static_cast<T>(v);
    } else if constexpr (std::is_same_v<T, bool>) {
      double v = value ? 1.0 : 0.0;
      Number(v);
      if constexpr (Op == StateOp::kLoad) value = v != 0.0;
    } else if constexpr (std::is_integral_v<T>) {
      Integer(value);
    } else if constexpr (std::is_enum_v<T>) {
      auto raw = static_cast<std::underlying_type_t<T>>(value);
      Integer(raw);
      if constexpr (Op == StateOp::kLoad) value = static_cast<T>(raw);
    } else if constexpr (std::is_array_v<T>) {
      for (auto& element : value) Visit(element);
    } else if constexpr (state_detail::IsRandomEngine<T>::value) {
      RandomEngine(value);
    } else if constexpr (state_detail::IsContiguous<T>::value) {
      auto* data = value.data();
      const size_t n = static_cast<size_t>(value.size());
      if constexpr (std::is_same_v<std::remove_cv_t<std::remove_pointer_t<decltype(data)>>,
                                   double>) {
        Doubles(data, n);  // a filter's matrices: one copy, not a call per number
      } else {
        for (size_t k = 0; k < n; ++k) Visit(data[k]);
      }
    } else {
      static_assert(sizeof(T) == 0,
                    "this member cannot be visited as state: give its type a VisitState member "
                    "or visit its members one by one");
    }
  }

  double* cursor_ = nullptr;
  size_t count_ = 0;
};

// The number of doubles T's VisitState lists.
template <typename T>
size_t StateSize(T& object) {
  StateVisitor<StateOp::kCount> visit;
  object.VisitState(visit);
  return visit.count();
}

// Writes T's state to out[0 .. StateSize(object) - 1].
template <typename T>
void GetState(T& object, double* out) {
  StateVisitor<StateOp::kSave> visit(out);
  object.VisitState(visit);
}

// Reads T's state back from in[0 .. StateSize(object) - 1].
template <typename T>
void SetState(T& object, const double* in) {
  StateVisitor<StateOp::kLoad> visit(const_cast<double*>(in));  // read only (kLoad)
  object.VisitState(visit);
}

// The three mjfPlugin callbacks of an instance of type Instance (ABI 4).
template <typename Instance>
size_t StateSizeOf(void* instance) {
  static_assert(kHasVisitState<Instance>,
                "a plugin instance lists its state: template <typename Visit> void "
                "VisitState(Visit& visit) (mjformation/plugin_state.hpp)");
  return StateSize(*static_cast<Instance*>(instance));
}
template <typename Instance>
void GetStateOf(void* instance, double* out) {
  GetState(*static_cast<Instance*>(instance), out);
}
template <typename Instance>
void SetStateOf(void* instance, const double* in) {
  SetState(*static_cast<Instance*>(instance), in);
}

}  // namespace mjf::plugin

#endif  // MJFORMATION_PLUGIN_STATE_HPP_
