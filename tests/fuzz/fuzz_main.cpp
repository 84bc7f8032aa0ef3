// SPDX-License-Identifier: Apache-2.0
// One libFuzzer executable per target: FLATSAT_FUZZ_ENTRY names its entry
// point (tests/fuzz/FuzzTargets.hpp).
#include "tests/fuzz/FuzzTargets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  flatsat::fuzz::FLATSAT_FUZZ_ENTRY(data, size);
  return 0;
}
