// SPDX-License-Identifier: Apache-2.0
#include "components/device_bridge/SerialPort.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace flatsat::device_bridge {

namespace {
speed_t speedFor(std::uint32_t baud, const std::string& what) {
  switch (baud) {
    case 921600: return B921600;
    case 460800: return B460800;
    case 230400: return B230400;
    case 115200: return B115200;
    case 57600: return B57600;
    case 38400: return B38400;
    case 19200: return B19200;
    case 9600: return B9600;
    case 4800: return B4800;
    case 2400: return B2400;
    case 1200: return B1200;
    default: throw std::runtime_error(what + ": unsupported baud rate " + std::to_string(baud));
  }
}

/// Unix 98 pseudo-terminal slaves (Linux devices.txt: majors 136..143) carry bytes, not
/// bits: Linux keeps PARENB clear on them, and glibc's tcsetattr reports EINVAL when parity
/// was the only change asked for (a second end opening a line set up already).
bool isPseudoTerminal(int fd) {
  struct stat st {};
  return ::fstat(fd, &st) == 0 && S_ISCHR(st.st_mode) && major(st.st_rdev) >= 136 && major(st.st_rdev) <= 143;
}

}  // namespace

void makeRaw(int fd, const device_protocol::LineSettings& line, const std::string& what) {
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    throw std::runtime_error(what + ": not a terminal: " + std::strerror(errno));
  }
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CSIZE | CSTOPB | CRTSCTS | PARENB | PARODD);
  tio.c_cflag |= CS8;  // LineSettings: binary frames, 8 data bits
  if (line.stop_bits == 2) tio.c_cflag |= CSTOPB;
  if (line.parity != "none" && !isPseudoTerminal(fd)) {
    tio.c_cflag |= PARENB | (line.parity == "odd" ? PARODD : 0);
    tio.c_iflag |= INPCK;  // a byte with a parity error reads as 0, which the frame's check refuses
  }
  const speed_t speed = speedFor(line.baud, what);
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  if (tcsetattr(fd, TCSANOW, &tio) != 0) {
    throw std::runtime_error(what + ": cannot set raw mode: " + std::strerror(errno));
  }
}

SerialPort::SerialPort(const std::string& path, const device_protocol::LineSettings& line) {
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  try {
    makeRaw(fd_, line, path);
    tcflush(fd_, TCIFLUSH);  // what the device sent before we listened is stale
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

long SerialPort::read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) {
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (ready == 0 || (ready < 0 && errno == EINTR)) return 0;
  if (ready < 0 || (p.revents & (POLLERR | POLLNVAL))) return -1;
  const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
  if (n > 0) return n;
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  return -1;  // hang-up: the device end closed
}

bool SerialPort::write(std::span<const std::uint8_t> bytes) {
  return ::write(fd_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
}

}  // namespace flatsat::device_bridge
