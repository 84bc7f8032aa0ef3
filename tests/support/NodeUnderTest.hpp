// SPDX-License-Identifier: Apache-2.0
#pragma once
// The frame of a component-tier node test: two participants on the test's own
// domain, loopback (the script's, which plays the node's peers, and the
// node's), and the two run to the end, the time master on the test's thread.
#include <string>
#include <thread>

#include "bus/Bus.hpp"
#include "tests/support/TestDomain.hpp"

namespace flatsat::test {

struct NodeTestBuses {
  /// `script_name`: the scripted peers' participant ("script": FedByScript.hpp
  /// makes the node take it as every topic's producer).
  explicit NodeTestBuses(const std::string& node_name, const std::string& script_name = "script")
      : script({testDomain(), bus::NetworkProfile::kLoopback, script_name}),
        node({testDomain(), bus::NetworkProfile::kLoopback, node_name}) {}
  bus::Bus script;
  bus::Bus node;
};

/// Runs `other` on a thread of its own and the time master `master` on this one, both to the end.
template <class Master, class Other>
void runTogether(Master& master, Other& other) {
  std::thread other_thread([&] { other.run(); });
  master.run();
  other_thread.join();
}

}  // namespace flatsat::test
