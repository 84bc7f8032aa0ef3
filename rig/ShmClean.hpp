// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <string>
#include <vector>

namespace flatsat::rig {

/// Removes Fast DDS shared-memory files in /dev/shm that no live process
/// maps: the data-sharing segments (fast_datasharing_*) of killed writers,
/// which `fastdds shm clean` (2.9) leaves, and the transport's segments
/// (fastrtps_*) and port mutexes (sem.fastrtps_*). Files younger than `min_age` stay: a process of another rig
/// starting at this moment creates its segments before it maps them, and a
/// parallel run (ctest -j2) must not lose them. Returns the names removed.
std::vector<std::string> cleanStaleSharedMemory(std::chrono::seconds min_age);

/// The age below which a launcher leaves an unused segment alone.
inline constexpr std::chrono::seconds kShmGrace{10};

}  // namespace flatsat::rig
