// SPDX-License-Identifier: Apache-2.0
#include "bus/Security.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace flatsat::bus {

namespace fs = std::filesystem;

namespace {

/// The file's URI for a security property; it must exist.
std::string fileUri(const fs::path& file, const std::string& what) {
  if (!fs::is_regular_file(file)) {
    throw std::invalid_argument("DDS Security: " + file.string() + " (" + what +
                                ") does not exist; make it with deploy/security/make-certs.sh");
  }
  return "file://" + fs::absolute(file).string();
}

}  // namespace

void addSecurity(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& dir,
                 const std::string& identity) {
  const fs::path root(dir);
  const fs::path own = root / identity;
  auto& properties = qos.properties().properties();
  const auto set = [&](const std::string& name, const std::string& value) {
    properties.emplace_back(name, value);
  };
  // Property names: Fast DDS 2.9 documentation, "Security" (DDS-Security 1.1 §9.3.1, §9.4.1).
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", fileUri(root / "identity_ca.pem", "identity CA"));
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate",
      fileUri(own / "cert.pem", "certificate of " + identity));
  set("dds.sec.auth.builtin.PKI-DH.private_key", fileUri(own / "key.pem", "key of " + identity));
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca",
      fileUri(root / "permissions_ca.pem", "permissions CA"));
  set("dds.sec.access.builtin.Access-Permissions.governance",
      fileUri(root / "governance.p7s", "signed governance"));
  set("dds.sec.access.builtin.Access-Permissions.permissions",
      fileUri(own / "permissions.p7s", "signed grant of " + identity));
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

std::string securityDirFromEnvironment() {
  const char* dir = std::getenv("FLATSAT_SECURE_DIR");
  return dir == nullptr ? std::string() : std::string(dir);
}

}  // namespace flatsat::bus
