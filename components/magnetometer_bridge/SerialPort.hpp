// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <cstdint>
#include <span>
#include <string>

namespace flatsat::magnetometer_bridge {

/// A serial line in raw mode (8N1, no flow control, no echo) at a baud rate:
/// a real port (/dev/ttyUSB0) or a pseudo-terminal's slave end. Closes on
/// destruction.
class SerialPort {
 public:
  /// @throws std::runtime_error naming the path and the reason
  SerialPort(const std::string& path, int baud);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Bytes read into buffer within the timeout (0: none came); -1 when the line
  /// is gone (the other end closed).
  long read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout);

 private:
  int fd_ = -1;
};

/// Puts a terminal file descriptor into raw 8N1 mode at the baud rate
/// (115200, 57600, 38400, 19200 or 9600). @throws std::runtime_error otherwise.
void makeRaw(int fd, int baud, const std::string& what);

}  // namespace flatsat::magnetometer_bridge
