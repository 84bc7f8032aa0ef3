// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>
#include <vector>

namespace flatsat::tools {

/// Removes Fast DDS shared-memory files in /dev/shm that no live process
/// maps: the data-sharing segments (fast_datasharing_*) of killed writers,
/// which `fastdds shm clean` (2.9) leaves, and the transport segments
/// (fastrtps_*). Returns the names removed.
std::vector<std::string> cleanStaleSharedMemory();

}  // namespace flatsat::tools
