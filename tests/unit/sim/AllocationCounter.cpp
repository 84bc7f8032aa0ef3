// SPDX-License-Identifier: Apache-2.0
// Replaces the global operator new / delete of the unit-test binary with
// counting wrappers of malloc / free (in a file of their own, so that the
// compiler never inlines them into test code).
#include "tests/unit/sim/AllocationCounter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace flatsat::sim::test {

long long allocationCount() { return g_allocations.load(std::memory_order_relaxed); }

}  // namespace flatsat::sim::test
