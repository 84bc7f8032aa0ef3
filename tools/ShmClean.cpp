// SPDX-License-Identifier: Apache-2.0
#include "tools/ShmClean.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>

namespace flatsat::tools {

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

std::vector<std::string> cleanStaleSharedMemory() {
  std::vector<std::string> removed;
  // A segment created after the scan of /proc below is in use but not in
  // `used`: only older ones may go (a rig starting beside this one lost its
  // live segments otherwise; seen with ctest -j2).
  const auto scan_start = fs::file_time_type::clock::now() - std::chrono::seconds(2);
  const auto used = filesInUse();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/dev/shm", ec)) {
    const auto name = entry.path().filename().string();
    const bool fastdds = name.rfind("fast_datasharing_", 0) == 0 || name.rfind("fastrtps_", 0) == 0;
    if (!fastdds || used.count(name) != 0) continue;
    std::error_code time_error;
    const auto modified = fs::last_write_time(entry.path(), time_error);
    if (time_error || modified >= scan_start) continue;
    if (fs::remove(entry.path(), ec)) removed.push_back(name);
  }
  return removed;
}

}  // namespace flatsat::tools
