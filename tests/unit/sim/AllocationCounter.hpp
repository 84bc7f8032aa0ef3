// SPDX-License-Identifier: Apache-2.0
#pragma once
// The unit tests' global operator new counts its calls (AllocationCounter.cpp),
// so that a test can show that a step allocates nothing.

namespace flatsat::sim::test {

/// [-] Calls of the ordinary operator new so far, in every thread.
long long allocationCount();

}  // namespace flatsat::sim::test
