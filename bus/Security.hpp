// SPDX-License-Identifier: Apache-2.0
#pragma once
// DDS Security (OMG DDS-Security 1.1, §9: the builtin PKI-DH authentication,
// Access-Permissions access control and AES-GCM-GMAC cryptography, all in
// Debian's Fast DDS 2.9.1) for a participant, from a directory made by
// deploy/security/make-certs.sh:
//   identity_ca.pem      CA of every participant's identity
//   permissions_ca.pem   a separate CA that signs governance and grants
//   governance.p7s       the domain's rules, S/MIME signed
//   <identity>/cert.pem, key.pem, permissions.p7s
// Two CAs, because Fast DDS 2.9.1 accepts a permissions document signed by
// any certificate chaining to the permissions CA: with one CA, a participant
// could sign its own grant with its identity key.
#include <string>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace flatsat::bus {

/// Identity of the operator tools (flatsat cmd, replay, echo, ...).
inline constexpr const char* kOperatorIdentity = "operator";

/// Adds the security plugins' properties for `identity` to `qos`. Throws
/// std::invalid_argument naming the file when one is missing.
void addSecurity(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& dir,
                 const std::string& identity);

/// FLATSAT_SECURE_DIR (set by `flatsat run --secure DIR`), "" when unset: open bus.
std::string securityDirFromEnvironment();

}  // namespace flatsat::bus
