// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <cstdint>
#include <span>
#include <string>

#include "components/device_protocol/DeviceProtocol.hpp"

namespace flatsat::device_bridge {

/// A serial line in raw mode (no flow control, no echo) with a device's line settings:
/// a real port (/dev/ttyUSB0) or a pseudo-terminal's slave end (which ignores the
/// settings). Closes on destruction.
class SerialPort {
 public:
  /// @throws std::runtime_error naming the path and the reason
  SerialPort(const std::string& path, const device_protocol::LineSettings& line);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Bytes read into buffer within the timeout (0: none came); -1 when the line
  /// is gone (the other end closed).
  long read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout);
  /// Writes `bytes` whole without waiting; false when the line is gone or its buffer
  /// cannot take them now (a device that stopped reading, as a real UART overruns).
  bool write(std::span<const std::uint8_t> bytes);

 private:
  int fd_ = -1;
};

/// Puts a terminal file descriptor into raw mode with the line's rate, character size,
/// parity and stop bits (LineSettings::validate()). @throws std::runtime_error otherwise.
void makeRaw(int fd, const device_protocol::LineSettings& line, const std::string& what);

}  // namespace flatsat::device_bridge
