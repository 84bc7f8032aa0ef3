// SPDX-License-Identifier: Apache-2.0
// An example flight computer: the software of an ADCS board that knows nothing of
// flatsat. It speaks only serial lines: it reads the magnetometer, gyro, Sun sensor and
// wheel-tachometer frames whose layouts the units' data sheets give (the comments of
// deploy/devices/*.yaml; every decoder and check here is its own), runs a Sun-pointing
// controller on four reaction wheels and a cross-product momentum unloading law on three
// magnetorquers, and writes wheel-torque and dipole command frames. Plain C++17 and POSIX:
// no DDS, no flatsat header, no library beyond the C++ standard one.
//
// The rig meets it through its lines (deploy/scenarios/hil_flight_computer.yaml): device
// stand-ins play its sensors, fed by the rig's emulators, and bridges carry its commands
// onto the bus. On a real board the same program runs with /dev/ttyS* or /dev/ttyUSB*
// paths (docs/devices.md, "A flight computer in the loop").
//
// usage: example_flight_computer --magnetometer TTY --gyro TTY --sun-sensor TTY
//            --wheel-tach TTY --wheel-torque-link PATH --dipole-link PATH
//   inputs are opened (waiting up to 30 s for each to appear); each output is a new
//   pseudo-terminal published as a symlink at its link path, for the rig's bridge to open.
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

// ---- Checks: CRCs in the Rocksoft model, computed bit by bit, and an 8-bit sum. ----

std::uint32_t reflect(std::uint32_t v, int bits) {
  std::uint32_t r = 0;
  for (int i = 0; i < bits; ++i) r |= ((v >> i) & 1u) << (bits - 1 - i);
  return r;
}

struct Crc {
  int width;
  std::uint32_t poly, init;
  bool refin, refout;
  std::uint32_t xorout;

  std::uint32_t of(const std::uint8_t* data, std::size_t n) const {
    const std::uint32_t mask = width == 32 ? 0xFFFFFFFFu : ((1u << width) - 1u);
    const std::uint32_t top = 1u << (width - 1);
    std::uint32_t reg = init;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t byte = refin ? reflect(data[i], 8) : data[i];
      reg ^= byte << (width - 8);
      for (int b = 0; b < 8; ++b) reg = ((reg & top) ? (reg << 1) ^ poly : (reg << 1)) & mask;
    }
    if (refout) reg = reflect(reg, width);
    return (reg ^ xorout) & mask;
  }
};

// The catalogue entries the units use (reveng.sourceforge.io "CRC catalogue").
const Crc kCrc16CcittFalse{16, 0x1021, 0xFFFF, false, false, 0};   // magnetometer; check 0x29B1
const Crc kCrc32Mpeg2{32, 0x04C11DB7, 0xFFFFFFFF, false, false, 0};  // gyro; check 0x0376E6E7
const Crc kCrc16Modbus{16, 0x8005, 0xFFFF, true, true, 0};           // Sun sensor; check 0x4B37
const Crc kCrc16Xmodem{16, 0x1021, 0x0000, false, false, 0};         // our commands; check 0x31C3

/// The 8-bit sum's complement (the wheel electronics' check).
std::uint8_t sumComplement(const std::uint8_t* data, std::size_t n) {
  unsigned sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += data[i];
  return static_cast<std::uint8_t>(~sum);
}

bool checksSelfTest() {
  const auto* text = reinterpret_cast<const std::uint8_t*>("123456789");
  return kCrc16CcittFalse.of(text, 9) == 0x29B1 && kCrc32Mpeg2.of(text, 9) == 0x0376E6E7 &&
         kCrc16Modbus.of(text, 9) == 0x4B37 && kCrc16Xmodem.of(text, 9) == 0x31C3;
}

// ---- Byte order ----

std::uint32_t le(const std::uint8_t* p, int n) {
  std::uint32_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
std::uint32_t be(const std::uint8_t* p, int n) {
  std::uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}
std::int32_t signedOf(std::uint32_t v, int bytes) {
  const int shift = 32 - 8 * bytes;
  return static_cast<std::int32_t>(v << shift) >> shift;
}
void putLe(std::vector<std::uint8_t>& out, std::uint32_t v, int n) {
  for (int i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void putF32(std::vector<std::uint8_t>& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  putLe(out, bits, 4);
}

// ---- A fixed-length frame off a byte stream: sync, then whatever `accept` says. ----

struct FrameReader {
  std::string name;
  std::vector<std::uint8_t> sync;
  std::size_t length;
  /// Checks and decodes a whole candidate frame; false: not a frame (bad header or check).
  std::function<bool(const std::uint8_t*)> accept;
  std::vector<std::uint8_t> buffer;
  unsigned long good = 0, bad = 0;

  void push(std::uint8_t byte) {
    buffer.push_back(byte);
    for (;;) {
      // Drop bytes until the buffer starts with (a prefix of) the sync.
      std::size_t keep = 0;
      while (keep < buffer.size() && keep < sync.size() && buffer[keep] == sync[keep]) ++keep;
      if (keep < sync.size() && keep < buffer.size()) {
        buffer.erase(buffer.begin());
        continue;
      }
      if (buffer.size() < length) return;
      if (accept(buffer.data())) {
        ++good;
        buffer.erase(buffer.begin(), buffer.begin() + static_cast<long>(length));
      } else {
        ++bad;
        buffer.erase(buffer.begin());  // a frame may start inside the broken one
      }
    }
  }
};

constexpr double kPi = 3.14159265358979323846;  // M_PI is an X/Open extension, not C++17

// ---- Serial lines ----

void makeRaw(int fd) {
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) return;
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tcsetattr(fd, TCSANOW, &tio);
}

int openInput(const std::string& path) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  for (;;) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd >= 0) {
      makeRaw(fd);
      tcflush(fd, TCIFLUSH);  // what the line held before the board listened is stale
      return fd;
    }
    if (g_stop || std::chrono::steady_clock::now() > deadline) {
      std::fprintf(stderr, "flight computer: cannot open %s: %s\n", path.c_str(), std::strerror(errno));
      std::exit(1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

/// A new pseudo-terminal whose slave end is published at `link`; returns the master.
int openOutput(const std::string& link, int& slave) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) {
    std::fprintf(stderr, "flight computer: no pseudo-terminal: %s\n", std::strerror(errno));
    std::exit(1);
  }
  const std::string name = ::ptsname(master);
  slave = ::open(name.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);  // held: the line stays up
  if (slave < 0) {
    std::fprintf(stderr, "flight computer: cannot open %s: %s\n", name.c_str(), std::strerror(errno));
    std::exit(1);
  }
  makeRaw(slave);
  ::unlink(link.c_str());
  if (::symlink(name.c_str(), link.c_str()) != 0) {
    std::fprintf(stderr, "flight computer: cannot link %s: %s\n", link.c_str(), std::strerror(errno));
    std::exit(1);
  }
  return master;
}

// ---- What the board knows of its spacecraft (the default rig's: deploy/scenarios/default.yaml) ----

const double kWheelAxes[4][3] = {{0.3420201433, 0.0, 0.9396926208},
                                 {-0.3420201433, 0.0, 0.9396926208},
                                 {0.3420201433, 0.9396926208, 0.0},
                                 {-0.3420201433, 0.9396926208, 0.0}};
constexpr double kWheelInertia = 0.12;    // [kg m^2]
constexpr double kWheelMaxTorque = 0.2;   // [N m]
constexpr double kBodyMaxTorque = 0.15;   // [N m]
constexpr double kKp = 1.2;               // [N m / rad]
constexpr double kKd = 60.0;              // [N m s / rad]
constexpr double kUnloadGain = 0.002;     // [1/s]
constexpr double kMaxDipole = 150.0;      // [A m^2] per coil
constexpr int kUnloadEvery = 10;          // gyro samples per unloading update (1 Hz)

using Vec = std::array<double, 3>;
Vec cross(const Vec& a, const Vec& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// Wheel motor torques giving body torque `tau` (the body feels −Σ τ_i a_i): the least-norm
/// solution τ_w = −Aᵀ (A Aᵀ)⁻¹ τ, scaled down together when a wheel would exceed its limit.
std::array<double, 4> wheelTorques(const Vec& tau) {
  double m[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int w = 0; w < 4; ++w) m[i][j] += kWheelAxes[w][i] * kWheelAxes[w][j];
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  double inv[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
    }
  Vec y{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) y[static_cast<std::size_t>(i)] += inv[i][j] * tau[static_cast<std::size_t>(j)];
  std::array<double, 4> t{};
  double worst = 0.0;
  for (int w = 0; w < 4; ++w) {
    t[static_cast<std::size_t>(w)] = -(kWheelAxes[w][0] * y[0] + kWheelAxes[w][1] * y[1] + kWheelAxes[w][2] * y[2]);
    worst = std::max(worst, std::abs(t[static_cast<std::size_t>(w)]));
  }
  if (worst > kWheelMaxTorque) {
    for (auto& v : t) v *= kWheelMaxTorque / worst;
  }
  return t;
}

struct Sensors {
  Vec b_T{};             // magnetometer, body axes (its mounting is the identity on this spacecraft)
  bool have_b = false;
  Vec w_rad_s{};          // gyro, body axes
  Vec sun{};              // Sun sensor, body axes
  bool sun_valid = false;
  std::array<double, 4> wheel_rad_s{};
};

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> path;
  for (int i = 1; i + 1 < argc; i += 2) path[argv[i]] = argv[i + 1];
  for (const char* key : {"--magnetometer", "--gyro", "--sun-sensor", "--wheel-tach", "--wheel-torque-link", "--dipole-link"}) {
    if (!path.count(key)) {
      std::fprintf(stderr,
                   "usage: %s --magnetometer TTY --gyro TTY --sun-sensor TTY --wheel-tach TTY "
                   "--wheel-torque-link PATH --dipole-link PATH\n",
                   argv[0]);
      return 2;
    }
  }
  if (!checksSelfTest()) {
    std::fprintf(stderr, "flight computer: a check does not give its catalogue value\n");
    return 2;
  }
  std::signal(SIGTERM, onSignal);
  std::signal(SIGINT, onSignal);
  std::signal(SIGPIPE, SIG_IGN);

  Sensors s;
  int gyro_samples = 0;
  Vec dipole_Am2{};  // the unloading law's last output
  std::uint16_t torque_counter = 0, dipole_counter = 0;
  int torque_slave = -1, dipole_slave = -1;
  const int torque_out = openOutput(path["--wheel-torque-link"], torque_slave);
  const int dipole_out = openOutput(path["--dipole-link"], dipole_slave);
  unsigned long commands_written = 0, commands_dropped = 0;
  const auto send = [&](int fd, std::vector<std::uint8_t> frame, std::size_t check_from) {
    putLe(frame, kCrc16Xmodem.of(frame.data() + check_from, frame.size() - check_from), 2);
    if (::write(fd, frame.data(), frame.size()) == static_cast<ssize_t>(frame.size())) {
      ++commands_written;
    } else {
      ++commands_dropped;  // nobody reading yet: the line's buffer is full
    }
  };

  // Every gyro sample (10 Hz) closes the attitude loop; every tenth updates the unloading law.
  const auto control = [&] {
    const Vec x{1.0, 0.0, 0.0};
    const Vec error = s.sun_valid ? cross(x, s.sun) : Vec{};  // turns +x onto the Sun
    Vec tau{};
    for (std::size_t i = 0; i < 3; ++i) tau[i] = kKp * error[i] - kKd * s.w_rad_s[i];
    const double norm = std::sqrt(dot(tau, tau));
    if (norm > kBodyMaxTorque) {
      for (auto& v : tau) v *= kBodyMaxTorque / norm;
    }
    std::vector<std::uint8_t> torque = {0x46, 0x57};
    for (double t : wheelTorques(tau)) putF32(torque, t);
    putLe(torque, torque_counter++, 2);
    send(torque_out, torque, 2);

    if (!s.have_b) return;
    if (gyro_samples++ % kUnloadEvery == 0) {
      Vec h{};
      for (std::size_t w = 0; w < 4; ++w)
        for (std::size_t i = 0; i < 3; ++i) h[i] += kWheelInertia * s.wheel_rad_s[w] * kWheelAxes[w][i];
      // Cross-product law: m = k (h × B) / |B|², so that m × B = −k h⊥ drains the wheels.
      const double b2 = dot(s.b_T, s.b_T);
      dipole_Am2 = cross(h, s.b_T);
      for (auto& v : dipole_Am2) v = std::clamp(b2 > 0.0 ? kUnloadGain * v / b2 : 0.0, -kMaxDipole, kMaxDipole);
    }
    // Sent with every attitude command, held between updates: a command line that falls
    // silent for longer than its deadline hands the coils back to the rig's own law.
    std::vector<std::uint8_t> dipole = {0x46, 0x44};
    for (double v : dipole_Am2) putF32(dipole, v);
    dipole.push_back(1);  // active
    putLe(dipole, dipole_counter++, 2);
    send(dipole_out, dipole, 2);
  };

  std::vector<FrameReader> readers;
  // Magnetometer: AA 55, type 01, length 16, u32 counter, 3 × i32 nT, CRC-16/CCITT-FALSE over 2..19, LE.
  readers.push_back({"magnetometer", {0xAA, 0x55}, 22, [&](const std::uint8_t* f) {
    if (f[2] != 0x01 || f[3] != 16 || le(f + 20, 2) != kCrc16CcittFalse.of(f + 2, 18)) return false;
    for (int i = 0; i < 3; ++i) s.b_T[static_cast<std::size_t>(i)] = signedOf(le(f + 8 + 4 * i, 4), 4) * 1e-9;
    s.have_b = true;
    return true;
  }, {}});
  // Gyro: A5, id 93, 3 × i32 BE in 1e-6 deg/s, status, u8 counter, CRC-32/MPEG-2 over 1..15, BE.
  readers.push_back({"gyro", {0xA5}, 20, [&](const std::uint8_t* f) {
    if (f[1] != 0x93 || be(f + 16, 4) != kCrc32Mpeg2.of(f + 1, 15)) return false;
    for (int i = 0; i < 3; ++i) {
      s.w_rad_s[static_cast<std::size_t>(i)] = signedOf(be(f + 2 + 4 * i, 4), 4) * 1e-6 * kPi / 180.0;
    }
    control();
    return true;
  }, {}});
  // Sun sensor: EB 90, id 21, 3 × i16 LE in 1/32000, valid, u16 counter, CRC-16/MODBUS over 2..11, LE.
  readers.push_back({"sun_sensor", {0xEB, 0x90}, 14, [&](const std::uint8_t* f) {
    if (f[2] != 0x21 || le(f + 12, 2) != kCrc16Modbus.of(f + 2, 10)) return false;
    for (int i = 0; i < 3; ++i) s.sun[static_cast<std::size_t>(i)] = signedOf(le(f + 3 + 2 * i, 2), 2) / 32000.0;
    s.sun_valid = f[9] != 0;
    return true;
  }, {}});
  // Wheel tachometers: C3 3C, 4 × i32 LE in mrad/s, u8 counter, complemented sum over 2..18.
  readers.push_back({"wheel_tach", {0xC3, 0x3C}, 20, [&](const std::uint8_t* f) {
    if (f[19] != sumComplement(f + 2, 17)) return false;
    for (int i = 0; i < 4; ++i) s.wheel_rad_s[static_cast<std::size_t>(i)] = signedOf(le(f + 2 + 4 * i, 4), 4) * 1e-3;
    return true;
  }, {}});
  std::vector<pollfd> fds;
  for (const char* key : {"--magnetometer", "--gyro", "--sun-sensor", "--wheel-tach"}) {
    fds.push_back({openInput(path[key]), POLLIN, 0});
  }
  std::fprintf(stderr, "flight computer: up; commands on %s and %s\n", path["--wheel-torque-link"].c_str(),
               path["--dipole-link"].c_str());

  auto next_report = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  const auto report = [&] {
    std::fprintf(stderr, "flight computer:");
    for (const auto& r : readers) std::fprintf(stderr, " %s %lu good %lu bad;", r.name.c_str(), r.good, r.bad);
    std::fprintf(stderr, " commands %lu written %lu dropped\n", commands_written, commands_dropped);
  };
  std::array<std::uint8_t, 256> bytes{};
  while (!g_stop) {
    if (::poll(fds.data(), fds.size(), 100) < 0 && errno != EINTR) break;
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].revents & (POLLERR | POLLNVAL)) {
        std::fprintf(stderr, "flight computer: line of the %s failed\n", readers[i].name.c_str());
        g_stop = 1;
        continue;
      }
      if (!(fds[i].revents & (POLLIN | POLLHUP))) continue;
      const ssize_t n = ::read(fds[i].fd, bytes.data(), bytes.size());
      for (ssize_t k = 0; k < n; ++k) readers[i].push(bytes[static_cast<std::size_t>(k)]);
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
        std::fprintf(stderr, "flight computer: line of the %s lost\n", readers[i].name.c_str());
        g_stop = 1;
      }
    }
    if (std::chrono::steady_clock::now() >= next_report) {
      report();
      next_report += std::chrono::seconds(10);
    }
  }
  report();
  ::unlink(path["--wheel-torque-link"].c_str());
  ::unlink(path["--dipole-link"].c_str());
  return 0;
}
