// SPDX-License-Identifier: Apache-2.0
// A process's network from its environment (bus/Bus.hpp BusNetwork): no DDS.
#include <catch2/catch.hpp>

#include "bus/Bus.hpp"
#include "tests/support/ScopedEnv.hpp"

using namespace flatsat::bus;

using flatsat::test::ScopedEnv;

TEST_CASE("FLATSAT_SHARED_MEMORY=0 takes shared memory out of the bus, and another value is refused by name",
          "[bus][network]") {
  const ScopedEnv no_peers("FLATSAT_PEERS", nullptr), no_servers("FLATSAT_DISCOVERY_SERVER", nullptr),
      no_network("FLATSAT_NETWORK", nullptr);
  {
    const ScopedEnv unset("FLATSAT_SHARED_MEMORY", nullptr);
    CHECK(networkFromEnvironment().shared_memory);
  }
  {
    const ScopedEnv off("FLATSAT_SHARED_MEMORY", "0");
    const BusNetwork network = networkFromEnvironment();
    CHECK(network.profile == NetworkProfile::kLoopback);
    CHECK_FALSE(network.shared_memory);
    BusOptions options;
    useNetwork(options, network);
    CHECK_FALSE(options.shared_memory);
  }
  {
    const ScopedEnv on("FLATSAT_SHARED_MEMORY", "1");
    CHECK(networkFromEnvironment().shared_memory);
  }
  const ScopedEnv bad("FLATSAT_SHARED_MEMORY", "no");
  CHECK_THROWS_WITH(networkFromEnvironment(), "FLATSAT_SHARED_MEMORY='no': must be 0 or 1");
}
