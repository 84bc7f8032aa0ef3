// SPDX-License-Identifier: Apache-2.0
#include "rig/ShmClean.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>

namespace flatsat::rig {

namespace fs = std::filesystem;

namespace {

/// Every /dev/shm file some process has mapped or open.
std::set<std::string> filesInUse() {
  std::set<std::string> used;
  std::error_code ec;
  for (const auto& proc : fs::directory_iterator("/proc", ec)) {
    const auto pid = proc.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream maps(proc.path() / "maps");
    for (std::string line; std::getline(maps, line);) {
      const auto at = line.find("/dev/shm/");
      if (at != std::string::npos) used.insert(fs::path(line.substr(at)).filename().string());
    }
    for (const auto& fd : fs::directory_iterator(proc.path() / "fd", ec)) {
      const auto target = fs::read_symlink(fd.path(), ec).string();
      if (target.rfind("/dev/shm/", 0) == 0) used.insert(fs::path(target).filename().string());
    }
  }
  return used;
}

}  // namespace

std::vector<std::string> cleanStaleSharedMemory(std::chrono::seconds min_age) {
  std::vector<std::string> removed;
  const auto used = filesInUse();
  const auto now = fs::file_time_type::clock::now();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/dev/shm", ec)) {
    const auto name = entry.path().filename().string();
    // sem.fastrtps_*: a transport port's named mutex (a POSIX semaphore, mapped by its users).
    const bool fastdds = name.rfind("fast_datasharing_", 0) == 0 || name.rfind("fastrtps_", 0) == 0 ||
                         name.rfind("sem.fastrtps_", 0) == 0;
    if (!fastdds || used.count(name) != 0) continue;
    const auto modified = fs::last_write_time(entry.path(), ec);
    if (ec || now - modified < min_age) continue;
    if (fs::remove(entry.path(), ec)) removed.push_back(name);
  }
  return removed;
}

}  // namespace flatsat::rig
