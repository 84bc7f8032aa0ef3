// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/WebCommand.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "bus/Convert.hpp"
#include "tools/HealthTable.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

using TruthDef = std::remove_cvref_t<decltype(bus::topics::kTruth)>;

struct WebOptions {
  int port = 8765;
  int domain = -1;
  double seconds = 0.0;  // 0: until Ctrl-C
};

/// The page: a health table and two plots drawn on canvases from /state.
constexpr const char* kPage = R"html(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>flatsat live</title>
<style>
body { font-family: sans-serif; margin: 1em; }
table { border-collapse: collapse; } td, th { border: 1px solid #999; padding: 2px 8px; text-align: right; }
td:first-child, th:first-child, td.state, td.message { text-align: left; }
.gone { color: #b00; } canvas { border: 1px solid #999; margin: 0.5em 1em 0 0; }
</style></head>
<body>
<h1>flatsat live</h1>
<p id="status">waiting for the rig&hellip;</p>
<table id="health"><thead><tr><th>component</th><th>state</th><th>steps</th><th>lag</th><th>overruns</th><th>stale</th>
<th>deadlines</th><th>dropped</th><th>refused</th><th>age [s]</th><th>message</th></tr></thead><tbody></tbody></table>
<div>
<canvas id="rate" width="560" height="260" data-title="body rate |&omega;| [deg/s]"></canvas>
<canvas id="momentum" width="560" height="260" data-title="wheel momentum |h| [N m s]"></canvas>
</div>
<script>
function cell(row, text, cls) { const td = row.insertCell(); td.textContent = text; if (cls) td.className = cls; }
function plot(canvas, t, y) {
  const g = canvas.getContext('2d'), w = canvas.width, h = canvas.height, m = 46;
  g.clearRect(0, 0, w, h);
  g.fillText(canvas.dataset.title.replace('&omega;', '\u03c9'), m, 14);
  g.fillText('simulated time [s]', w / 2 - 40, h - 4);
  if (t.length < 2) return;
  const t0 = t[0], t1 = t[t.length - 1], ymax = Math.max(...y) * 1.1 || 1;
  g.strokeRect(m, 20, w - m - 10, h - m - 10);
  g.fillText(ymax.toPrecision(3), 2, 26); g.fillText('0', 30, h - m + 10);
  g.fillText(t0.toFixed(0), m, h - m + 22); g.fillText(t1.toFixed(0), w - 60, h - m + 22);
  g.beginPath();
  for (let i = 0; i < t.length; ++i) {
    const x = m + (w - m - 10) * (t[i] - t0) / (t1 - t0 || 1), yy = h - m - (h - m - 30) * y[i] / ymax;
    if (i === 0) g.moveTo(x, yy); else g.lineTo(x, yy);
  }
  g.stroke();
}
async function refresh() {
  try {
    const s = await (await fetch('/state')).json();
    const body = document.querySelector('#health tbody');
    body.innerHTML = '';
    for (const r of s.health) {
      const row = body.insertRow(); row.dataset.component = r.component;
      const flag = r.alive ? (r.late ? ' (late)' : '') : ' (gone)';
      cell(row, r.component); cell(row, r.state + flag, flag ? 'state gone' : 'state');
      cell(row, r.steps_done); cell(row, r.lag_steps); cell(row, r.overruns); cell(row, r.stale_inputs);
      cell(row, r.deadlines_missed); cell(row, r.samples_dropped);
      cell(row, r.commands_refused); cell(row, r.age_s.toFixed(1)); cell(row, r.message, 'message');
    }
    document.getElementById('status').textContent =
      s.health.length + ' components on domain ' + s.domain + ', ' + s.t_s.length + ' truth samples';
    plot(document.getElementById('rate'), s.t_s, s.rate_deg_s);
    plot(document.getElementById('momentum'), s.t_s, s.h_Nms);
  } catch (e) {
    document.getElementById('status').textContent = 'no answer from flatsat web: ' + e;
  }
}
refresh(); setInterval(refresh, 500);
</script></body></html>
)html";

/// What the page shows, gathered from the bus.
class LiveState {
 public:
  explicit LiveState(ToolBus& tool_bus)
      : tool_bus_(tool_bus),
        health_(tool_bus, mutex_, entries_),
        truth_(tool_bus.bus(), bus::topics::kTruth, [this](const msg::TruthState& t, const Arrival&) {
          std::lock_guard lock(mutex_);
          const double t_s = static_cast<double>(t.header().sim_time_ns()) * 1e-9;
          if (!points_.empty() && t_s <= points_.back().t_s) points_.clear();  // a new run
          // The last kPoints, thinned to one per simulated second past the first.
          if (!points_.empty() && t_s - points_.back().t_s < 1.0) return;
          points_.push_back({t_s, bus::vec3(t.w_body_rad_s()).norm() * 180.0 / M_PI,
                             bus::vec3(t.h_wheels_body_Nms()).norm()});
          if (points_.size() > kPoints) points_.pop_front();
        }) {}

  std::string json() const {
    std::lock_guard lock(mutex_);
    nlohmann::ordered_json s;
    s["domain"] = tool_bus_.domain();
    s["health"] = healthTable(entries_, tool_bus_);
    auto t = nlohmann::ordered_json::array(), rate = t, h = t;
    for (const auto& p : points_) {
      t.push_back(p.t_s);
      rate.push_back(p.rate_deg_s);
      h.push_back(p.h_Nms);
    }
    s["t_s"] = t;
    s["rate_deg_s"] = rate;
    s["h_Nms"] = h;
    return s.dump();
  }

 private:
  static constexpr std::size_t kPoints = 600;
  struct Point {
    double t_s, rate_deg_s, h_Nms;
  };
  ToolBus& tool_bus_;
  mutable std::mutex mutex_;
  std::map<std::string, HealthEntry> entries_;
  std::deque<Point> points_;
  HealthWatcher health_;
  bus::Reader<TruthDef> truth_;
};

void reply(int fd, const std::string& status, const std::string& type, const std::string& body) {
  const std::string head = "HTTP/1.1 " + status + "\r\nContent-Type: " + type +
                           "\r\nCache-Control: no-store\r\nConnection: close\r\nContent-Length: " +
                           std::to_string(body.size()) + "\r\n\r\n";
  const std::string all = head + body;
  for (std::size_t sent = 0; sent < all.size();) {
    const ssize_t n = ::send(fd, all.data() + sent, all.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

/// One request per connection: GET / (the page) or GET /state (JSON).
void serve(int fd, const LiveState& state) {
  char buffer[2048];
  const ssize_t n = ::recv(fd, buffer, sizeof(buffer) - 1, 0);
  if (n <= 0) return;
  buffer[n] = '\0';
  const std::string request(buffer);
  if (request.rfind("GET / ", 0) == 0 || request.rfind("GET /index.html ", 0) == 0) {
    reply(fd, "200 OK", "text/html; charset=utf-8", kPage);
  } else if (request.rfind("GET /state ", 0) == 0) {
    reply(fd, "200 OK", "application/json", state.json());
  } else {
    reply(fd, "404 Not Found", "text/plain", "not here: / and /state only\n");
  }
}

int web(const WebOptions& o) {
  ToolBus tool_bus("web", o.domain);
  LiveState state(tool_bus);
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  if (listener < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
  const int yes = 1;
  ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(o.port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // this host only
  if (::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 || ::listen(listener, 16) != 0) {
    const std::string why = std::strerror(errno);
    ::close(listener);
    throw std::runtime_error("--port " + std::to_string(o.port) + ": cannot listen on 127.0.0.1: " + why);
  }
  std::cout << "flatsat web: http://127.0.0.1:" << o.port << "/ (domain " << tool_bus.domain() << ")\n" << std::flush;
  const auto start = Clock::now();
  // One thread: each request is answered at once (the page and a small JSON).
  while (o.seconds <= 0.0 || std::chrono::duration<double>(Clock::now() - start).count() < o.seconds) {
    pollfd waiting{listener, POLLIN, 0};
    const int ready = ::poll(&waiting, 1, 200);
    if (ready < 0 && errno != EINTR) break;
    if (!sleepUnlessInterrupted(0.0)) break;
    if (ready <= 0) continue;
    const int fd = ::accept(listener, nullptr, nullptr);
    if (fd < 0) continue;
    serve(fd, state);
    ::close(fd);
  }
  ::close(listener);
  return 0;
}

}  // namespace

CLI::App* addWebCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<WebOptions>();
  auto* cmd = app.add_subcommand("web", "a live view of a running rig in the browser (127.0.0.1 only)");
  cmd->add_option("--port", options->port, "TCP port on 127.0.0.1 (default 8765)")->check(CLI::Range(1, 65535));
  cmd->add_option("--seconds", options->seconds, "stop after S seconds [s] (default: at Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  addDomainOption(*cmd, options->domain);
  cmd->footer(
      "Open http://127.0.0.1:PORT/: the health table (as `flatsat health`) and live plots of\n"
      "the body rate and the stored wheel momentum, refreshed twice a second; GET /state\n"
      "gives the same as JSON.");
  cmd->callback([options, &exit_code] { runReportingErrors(exit_code, [&] { return web(*options); }); });
  return cmd;
}

}  // namespace flatsat::tools
