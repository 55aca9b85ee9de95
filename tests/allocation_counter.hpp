#pragma once
// Counts every global operator new of the test executable that includes it. It replaces the
// global operators, so include it in exactly one translation unit of an executable of its own.

#include <atomic>
#include <cstdlib>
#include <new>

namespace stickslip_test {
/// Number of global operator new calls since the start of the program.
inline std::atomic<long> g_allocations{0};
}  // namespace stickslip_test

// The replaced operators pair malloc with free. GCC's -Wmismatched-new-delete cannot see that the
// replaced operator new is the one that allocated when it inlines delete into gtest's factories
// (later in the including file), so it is silenced for the rest of that file (a false positive).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t n) {
  ++stickslip_test::g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
