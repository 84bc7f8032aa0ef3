// SPDX-License-Identifier: Apache-2.0
#pragma once
// A node under test in the component tier is fed by scripted peers that share
// one participant, named "script", and publish several components' topics.
#include "bus/Node.hpp"

namespace flatsat::test {

/// The node's options with the script's participant taken as the producer of
/// every topic (NodeOptions::trusted), as FLATSAT_TRUST does for a replay.
inline bus::NodeOptions fedByScript(bus::NodeOptions options) {
  options.trusted.push_back("script");
  return options;
}

}  // namespace flatsat::test
