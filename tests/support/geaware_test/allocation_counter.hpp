// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Counts heap allocations, so a test can assert that a hot path (a control or simulation step,
// trajectory sampling, network inference) never allocates. It REPLACES the global allocation
// functions of the whole test executable: include it from exactly one source file per test
// executable. Replacements only count and forward; everything else behaves as usual.
//   operator new/new[] catch standard containers; Eigen's dynamic storage calls std::malloc
//   directly, so on glibc malloc itself is interposed too (forwarding to __libc_malloc).
// Under AddressSanitizer nothing is replaced: the sanitizer's allocator owns malloc and new (a
// malloc of ours would hand it blocks it never allocated, and it runs before the sanitizer's
// shadow memory exists: the executables crashed at start-up), and its allocation hook counts
// every allocation instead, new and malloc alike.

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace geaware_test {

/// Allocations so far in this process (all threads).
inline std::atomic<long> g_allocation_count{0};

[[nodiscard]] inline long allocationCount() noexcept {
  return g_allocation_count.load(std::memory_order_relaxed);
}

}  // namespace geaware_test

#if defined(__SANITIZE_ADDRESS__)
#define GEAWARE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GEAWARE_TEST_ASAN 1
#endif
#endif

#if defined(GEAWARE_TEST_ASAN)
// sanitizer/allocator_interface.h (not shipped with GCC 12's headers; the runtime has it).
extern "C" int __sanitizer_install_malloc_and_free_hooks(  // NOLINT(bugprone-reserved-identifier)
    void (*malloc_hook)(const volatile void*, std::size_t), void (*free_hook)(const volatile void*));

namespace geaware_test {
inline void countAllocation(const volatile void*, std::size_t) noexcept {
  g_allocation_count.fetch_add(1, std::memory_order_relaxed);
}
inline void ignoreFree(const volatile void*) noexcept {}
inline const int g_allocation_hook_installed =
    __sanitizer_install_malloc_and_free_hooks(&countAllocation, &ignoreFree);
}  // namespace geaware_test
#else
#if defined(__GLIBC__)
extern "C" void* __libc_malloc(std::size_t n);     // NOLINT(bugprone-reserved-identifier): glibc
extern "C" void* malloc(std::size_t n) noexcept {  // NOLINT(readability-inconsistent-*)
  geaware_test::g_allocation_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
#endif

// Not inlined: GCC would otherwise see free() applied to the result of a new-expression and warn
// (-Wmismatched-new-delete), not knowing these are the replacements themselves.
[[gnu::noinline]] void* operator new(std::size_t n) {
#if !defined(__GLIBC__)
  geaware_test::g_allocation_count.fetch_add(1, std::memory_order_relaxed);  // else malloc counts
#endif
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { ::operator delete(p); }
void operator delete(void* p, std::size_t) noexcept { ::operator delete(p); }
void operator delete[](void* p, std::size_t) noexcept { ::operator delete(p); }
#endif  // GEAWARE_TEST_ASAN
