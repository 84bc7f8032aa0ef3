// SPDX-License-Identifier: Apache-2.0
#pragma once
// A component test's participant under DDS Security.
#include <cstdint>
#include <string>

#include "bus/Bus.hpp"
#include "tests/support/Certificates.hpp"

namespace flatsat::test {

/// A participant of `identity` on `domain` with its certificate and grant from `certs`.
inline bus::BusOptions secured(const Certificates& certs, std::uint32_t domain, const std::string& identity) {
  return {.domain_id = domain, .participant_name = identity, .security_dir = certs.dir.string(), .identity = identity};
}

}  // namespace flatsat::test
