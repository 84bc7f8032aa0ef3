#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Makes what `flatsat run SCENARIO --secure DIR` needs (bus/Security.hpp):
#   make-certs.sh DIR [IDENTITY ...]
# Two CAs (identity, permissions), a signed governance document and, for
# each identity (default: every component kind, `operator` and `replay`), an
# ECDSA P-256 key, a certificate and a signed least-privilege grant.
#
# The grants come from `flatsat security-grants` (tools/GrantsCommand.hpp),
# made from the topic registry bus/Topics.hpp: a component may publish the
# topics it produces and what its code writes besides (health, step_done,
# command_ack, fault_event), a bridge its producer's topics, `operator` the
# commands (and fault_event), `replay` the stepped topics and grants; a
# component may subscribe to what its node reads, `operator` and `replay` to
# every registry topic. The tool is FLATSAT_TOOL,
# else `flatsat` on PATH, else build/bin/flatsat of the tree this script is in.
#
# DIR/private keeps the CA keys: re-running adds missing identities with the
# same CAs, keeps every existing key and certificate, and signs an identity's
# grant again only when its rules changed (a grant of an older make-certs.sh,
# which let every component publish every non-command topic, is replaced).
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: $0 DIR [IDENTITY ...]" >&2; exit 2; }
dir=$1; shift
for id in "$@"; do
  [[ "$id" =~ ^[a-z0-9_]+$ ]] || { echo "make-certs.sh: '$id': identities are [a-z0-9_]+" >&2; exit 2; }
done

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
tool=${FLATSAT_TOOL:-}
if [ -z "$tool" ]; then
  if command -v flatsat >/dev/null 2>&1; then
    tool=$(command -v flatsat)
  elif [ -x "$here/../../build/bin/flatsat" ]; then
    tool=$here/../../build/bin/flatsat
  else
    echo "make-certs.sh: the grants come from the flatsat tool (flatsat security-grants): set" \
         "FLATSAT_TOOL=/path/to/flatsat, put flatsat on PATH, or build it (build/bin/flatsat)" >&2
    exit 2
  fi
fi
grants=$("$tool" security-grants "$@") ||
  { echo "make-certs.sh: '$tool security-grants $*' failed: no grants made" >&2; exit 2; }
declare -A publish subscribe
identities=()
while read -r id verb topics; do
  case $verb in
    publish) publish[$id]=$topics; identities+=("$id") ;;
    subscribe) subscribe[$id]=$topics ;;
    *) echo "make-certs.sh: unexpected line from $tool security-grants: $id $verb" >&2; exit 2 ;;
  esac
done <<<"$grants"
[ ${#identities[@]} -gt 0 ] || { echo "make-certs.sh: $tool security-grants listed no identity" >&2; exit 2; }

days=3650
mkdir -p "$dir/private"
chmod 700 "$dir/private"

ca() {  # name subject
  [ -f "$dir/$1.pem" ] && return 0
  openssl ecparam -name prime256v1 -genkey -noout -out "$dir/private/$1_key.pem"
  openssl req -x509 -new -sha256 -key "$dir/private/$1_key.pem" -subj "$2" -days "$days" \
    -out "$dir/$1.pem"
}
ca identity_ca "/O=flatsat/CN=flatsat identity CA"
ca permissions_ca "/O=flatsat/CN=flatsat permissions CA"

sign() {  # in.xml out.p7s: S/MIME, signed by the permissions CA (DDS-Security 1.1 §9.4.1.2)
  openssl smime -sign -in "$1" -text -out "$2" -signer "$dir/permissions_ca.pem" \
    -inkey "$dir/private/permissions_ca_key.pem"
}

domains='<domains><id_range><min>0</min><max>232</max></id_range></domains>'
topic_list() { for t in "$@"; do printf '<topic>%s</topic>' "$t"; done; }

# Governance (DDS-Security 1.1 §9.4.1.2.3): only authenticated participants
# join; every topic's discovery, metadata and data are encrypted, and read
# and write access are checked against the grants.
if [ ! -f "$dir/governance.p7s" ]; then
  cat > "$dir/governance.xml" <<XML
<?xml version="1.0" encoding="utf-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="omg_shared_ca_domain_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $domains
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>SIGN</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
  sign "$dir/governance.xml" "$dir/governance.p7s"
fi

not_before=$(date -u -d '-1 day' +%Y-%m-%dT%H:%M:%S)
not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)
# Readers read in the default partition, where every writer of the rig is, and in the one a
# process holds its liveliness watchers in while it makes or deletes a reader
# (bus::Bus::createReader; no writer is allowed there).
subscribe_partitions="<partitions><partition></partition><partition>flatsat.watchers-held</partition></partitions>"
written=0
for id in "${identities[@]}"; do
  own="$dir/$id"
  mkdir -p "$own"
  if [ ! -f "$own/cert.pem" ] || [ ! -f "$own/key.pem" ]; then
    openssl ecparam -name prime256v1 -genkey -noout -out "$own/key.pem"
    chmod 600 "$own/key.pem"
    openssl req -new -sha256 -key "$own/key.pem" -subj "/O=flatsat/CN=$id" -out "$own/cert.csr"
    openssl x509 -req -sha256 -in "$own/cert.csr" -CA "$dir/identity_ca.pem" \
      -CAkey "$dir/private/identity_ca_key.pem" -CAcreateserial -days "$days" -out "$own/cert.pem" \
      2>/dev/null
    rm -f "$own/cert.csr"
  fi
  # The grant (DDS-Security 1.1 §9.4.1.3): the first matching rule wins, anything else is denied.
  # shellcheck disable=SC2086  # the topic lists split at spaces
  rules="<allow_rule>$domains<publish><topics>$(topic_list ${publish[$id]})</topics></publish><subscribe><topics>$(topic_list ${subscribe[$id]:-})</topics>$subscribe_partitions</subscribe></allow_rule>"
  if [ -f "$own/permissions.p7s" ] && [ -f "$own/permissions.xml" ] &&
     grep -qF -- "$rules" "$own/permissions.xml"; then
    continue  # signed with these rules already
  fi
  [ -f "$own/permissions.p7s" ] && echo "make-certs.sh: $id: its grant's rules changed; signing the new ones" >&2
  cat > "$own/permissions.xml" <<XML
<?xml version="1.0" encoding="utf-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$id">
      <subject_name>CN=$id,O=flatsat</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>
      $rules
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
  sign "$own/permissions.xml" "$own/permissions.p7s"
  written=$((written + 1))
done
echo "make-certs.sh: ${#identities[@]} identities in $dir ($written grants signed)" >&2
