# SPDX-License-Identifier: Apache-2.0
# Sourced by the shell tests that open DDS: exports FLATSAT_DOMAIN, a domain of
# this test's own, held by a lock on file descriptor 9 to the test's end, as
# tests/support/TestDomain.hpp holds one for the C++ tests (the same domains,
# the same lock files): two tests on one domain would share a bus.
for _i in $(seq 0 109); do
  FLATSAT_DOMAIN=$((10 + 2 * (($$ + _i) % 110)))
  exec 9>"/tmp/flatsat-test-domain-$FLATSAT_DOMAIN.lock"
  flock -n 9 && break
done
export FLATSAT_DOMAIN
