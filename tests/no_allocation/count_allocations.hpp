// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Counts malloc, calloc and realloc while `counting` is set, by replacing them for the whole
// binary (glibc's own entry points do the work). Include it in exactly one source file of a test
// executable: the definitions below are the binary's malloc. Replacing malloc is what the
// sanitizers do too, so tests/no_allocation is built only without them.
#ifndef MJFORMATION_TESTS_COUNT_ALLOCATIONS_HPP_
#define MJFORMATION_TESTS_COUNT_ALLOCATIONS_HPP_

#include <atomic>
#include <cstddef>

#if defined(__SANITIZE_ADDRESS__)
#error "allocation counting needs the uninstrumented allocator: build without MJF_SANITIZE"
#endif

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void __libc_free(void*);
void* malloc(size_t size) {
  if (counting.load(std::memory_order_relaxed)) ++allocations;
  return __libc_malloc(size);
}
void* calloc(size_t n, size_t size) {
  if (counting.load(std::memory_order_relaxed)) ++allocations;
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t size) {
  if (counting.load(std::memory_order_relaxed)) ++allocations;
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
}

#endif  // MJFORMATION_TESTS_COUNT_ALLOCATIONS_HPP_
