// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/PlotCommand.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>

#include "analysis/PlotData.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace flatsat::tools {

using analysis::DipoleRow;
using analysis::EstimateRow;
using analysis::EventRow;
using analysis::MagnetometerRow;
using analysis::PlotContext;
using analysis::PlotData;
using analysis::TruthRow;
using analysis::readPlotContext;
using analysis::readPlotData;

namespace {

struct PlotOptions {
  std::string recording;
  std::string out;       ///< empty: <recording's folder>/plots
  std::string scenario;  ///< empty: scenario.yaml next to the recording, if there
  std::size_t max_points = 20000;
  bool list = true;  ///< print each PNG's path
};

/// gnuplot single-quoted string (a file name, a label): a quote is doubled.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

/// Writes every `stride`-th row (and the last) of a series; a row writer
/// returns false to break the line there (a blank line for gnuplot).
template <class Row>
void writeData(const fs::path& file, const std::vector<Row>& rows, std::size_t max_points,
               const std::function<void(std::FILE*, const Row&)>& write) {
  std::FILE* f = std::fopen(file.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write " + file.string());
  const std::size_t stride = std::max<std::size_t>(1, (rows.size() + max_points - 1) / max_points);
  for (std::size_t i = 0; i < rows.size(); i += stride) write(f, rows[i]);
  if (!rows.empty() && (rows.size() - 1) % stride != 0) write(f, rows.back());
  std::fclose(f);
}

struct TimeAxis {
  double scale;  ///< [unit/s]
  std::string label;
};

TimeAxis timeAxis(const PlotData& d) {
  const double end = d.truth.empty() ? 0.0 : d.truth.back().t_s;
  if (end > 3 * 3600) return {1.0 / 3600, "simulated time [h]"};
  if (end > 1200) return {1.0 / 60, "simulated time [min]"};
  return {1.0, "simulated time [s]"};
}

/// The gnuplot script being written: its stream, where its data files are,
/// the time axis and the PNGs it makes.
struct FigureScript {
  std::ofstream s;
  fs::path out;
  fs::path data;
  TimeAxis ta;
  std::vector<std::string> pngs;

  const std::vector<EventRow>* events = nullptr;

  std::string dat(const char* name) const { return quoted(data / name); }
  /// Starts a figure: fixed side margins, so the panels of one figure line up;
  /// the legend above each panel, where it covers no data and stays in the
  /// frame whatever its length (below, gnuplot 5.4 sets it over the axis
  /// label); the run's events marked on a time axis.
  void begin(const std::string& png, const std::string& title, bool time_axis = true) {
    pngs.push_back(png);
    s << "\nreset\nset output " << quoted(out / png)
      << "\nset grid\nset key above horizontal box width 2\nset lmargin 12\nset rmargin 6\n"
      << "set xlabel '" << ta.label << "'\nset title \"" << title << "\"\n";
    if (time_axis && events != nullptr) markEvents();
  }

  /// A dotted line per event, labelled at the top of the panel; a run with
  /// many events gets lines only (their labels would overprint).
  void markEvents() {
    constexpr std::size_t kLabelledAtMost = 12;
    for (const auto& e : *events) {
      const double t = e.t_s * ta.scale;
      s << "set arrow from " << t << ", graph 0 to " << t << ", graph 1 nohead dt 3 lw 1.2 lc rgb '#7a0177' front\n";
      if (events->size() <= kLabelledAtMost) {
        s << "set label " << quoted(e.label.substr(0, 40)) << " at " << t
          << ", graph 0.97 rotate by 90 right offset -0.6,0 font ',9' tc rgb '#7a0177' front\n";
      }
    }
  }

  /// Panels below one title; the title's blank line keeps the first row's legend (above it) off the title.
  void multiplot(int rows, int columns, const std::string& title) {
    s << "set multiplot layout " << rows << "," << columns << " title \"";
    for (char ch : title) s << (ch == '"' || ch == '\\' ? "\\" : "") << ch;
    s << "\\n\"\n";
  }
};

/// Twelve colours told apart by anyone (Tableau 10, then two dark ones), so
/// the series of one figure (up to twelve thrusters) never share a colour.
constexpr const char* kSeriesColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                          "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000", "#393b79"};

/// `set yrange` that holds a constant series (gnuplot would widen [v:v] itself, with a warning).
std::string rangeHolding(const std::vector<double>& values) {
  if (values.empty()) return "set yrange [-1:1]\n";
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  if (*hi - *lo > 1e-12 * std::max(1.0, std::abs(*hi))) return "set autoscale y\n";
  std::ostringstream r;
  r << "set yrange [" << *lo - 1 << ":" << *hi + 1 << "]\n";
  return r.str();
}

/// Data files (gnuplot/*.dat) of every figure, at most max_points rows each.
void writeDataFiles(const PlotData& d, const PlotContext& c, const fs::path& data, const TimeAxis& ta,
                    std::size_t max_points) {

  const auto v3 = [](std::FILE* f, const Eigen::Vector3d& v) {
    std::fprintf(f, " %.7g %.7g %.7g", v.x(), v.y(), v.z());
  };
  writeData<TruthRow>(data / "truth.dat", d.truth, max_points, [&](std::FILE* f, const TruthRow& r) {
    std::fprintf(f, "%.7g %.7g", r.t_s * ta.scale, std::max(r.pointing_error_deg, 1e-6));
    v3(f, r.w_B_deg_s);
    for (double w : r.wheel_rad_s) std::fprintf(f, " %.7g", w);
    std::fprintf(f, " %.7g", r.h_wheels_Nms);
    v3(f, r.b_B_uT);
    v3(f, r.dipole_B_Am2);
    std::fprintf(f, " %.4g\n", r.illumination);
  });
  writeData<MagnetometerRow>(data / "magnetometer.dat", d.magnetometer, max_points,
                             [&](std::FILE* f, const MagnetometerRow& r) {
                               std::fprintf(f, "%.7g", r.t_s * ta.scale);
                               v3(f, r.b_B_uT);
                               v3(f, r.error_B_nT);
                               std::fprintf(f, "\n");
                             });
  writeData<EstimateRow>(data / "estimate.dat", d.estimate, max_points,
                         [&](std::FILE* f, const EstimateRow& r) {
                           std::fprintf(f, "%.7g %.7g", r.t_s * ta.scale, std::max(r.error_deg, 1e-7));
                           v3(f, r.error_B_deg);
                           v3(f, r.b_B_uT);
                           // The error's sign convention differs from the
                           // filter's (q_true = q exp(dθ/2)): the bound is symmetric.
                           v3(f, r.sigma3_B_deg.value_or(Eigen::Vector3d::Constant(NAN)));
                           std::fprintf(f, "\n");
                         });
  {
    // Every firing step: a stride would drop pulses.
    std::FILE* f = std::fopen((data / "thruster.dat").c_str(), "w");
    if (f == nullptr) throw std::runtime_error("cannot write " + data.string());
    for (const auto& r : d.thruster) {
      std::fprintf(f, "%.7g %.7g %d %d", r.t_s * ta.scale, r.total_on_time_s, r.pulse,
                   r.braking ? r.pulse : 0);
      for (double on : r.on_time_s) std::fprintf(f, " %.7g", on);
      std::fprintf(f, "\n");
    }
    std::fclose(f);
  }
  writeData<DipoleRow>(data / "dipole.dat", d.dipole, max_points, [&](std::FILE* f, const DipoleRow& r) {
    std::fprintf(f, "%.7g", r.t_s * ta.scale);
    v3(f, r.m_B_Am2);
    const Eigen::Vector3d duty =
        c.max_dipole_Am2 ? Eigen::Vector3d(r.m_B_Am2.cwiseAbs().cwiseQuotient(*c.max_dipole_Am2) * 100)
                         : Eigen::Vector3d::Zero();
    v3(f, duty);
    std::fprintf(f, " %d\n", r.active ? 1 : 0);
  });
  // Ground track: one file per lighting, the line broken at the date line and
  // where the lighting changes.
  for (const bool sunlit : {true, false}) {
    std::FILE* f = std::fopen((data / (sunlit ? "track_sun.dat" : "track_eclipse.dat")).c_str(), "w");
    if (f == nullptr) throw std::runtime_error("cannot write " + data.string());
    const std::size_t stride = std::max<std::size_t>(1, d.truth.size() / max_points);
    bool drawing = false;
    double last_lon = 0;
    for (std::size_t i = 0; i < d.truth.size() && d.track != PlotData::Track::kNone; i += stride) {
      const auto& r = d.truth[i];
      const bool in = (r.illumination >= 0.5) == sunlit;
      if (drawing && (!in || std::abs(r.lon_deg - last_lon) > 180)) std::fprintf(f, "\n");
      if (in) std::fprintf(f, "%.5f %.5f\n", r.lon_deg, r.lat_deg);
      drawing = in;
      last_lon = r.lon_deg;
    }
    std::fclose(f);
  }
}

void pointingFigure(FigureScript& f, const PlotData& d, const PlotContext& c) {
  std::ostringstream axis;
  axis << "[" << c.pointing_axis_B.transpose().format(Eigen::IOFormat(3, 0, " ")) << "]";
  const double acq = c.acquisition_s.value_or(-1) * f.ta.scale;
  f.begin("pointing_error.png", "Pointing error: angle between body axis " + axis.str() + " and the Sun (truth)");
  f.s << "set ylabel 'pointing error [deg]'\nset logscale y\n";
  if (acq > 0) f.s << "set arrow from " << acq << ", graph 0 to " << acq << ", graph 1 nohead dt 2 lc rgb 'gray30'\n";
  f.s << "plot " << f.dat("truth.dat") << " using 1:2 with lines lc rgb '#1f77b4' title 'pointing error'";
  if (acq > 0) f.s << ", NaN with lines dt 2 lc rgb 'gray30' title 'metrics start (acquisition_s)'";
  f.s << "\n";
}

void ratesFigure(FigureScript& f) {
  f.begin("body_rates.png", "Body rates w.r.t. inertial, body axes (truth)");
  f.s << "set ylabel 'body rate [deg/s]'\nplot " << f.dat("truth.dat") << " using 1:3 with lines title 'ω x', '' using 1:4 with lines title 'ω y', '' using 1:5 with lines title 'ω z'\n";
}

void wheelsFigure(FigureScript& f, const PlotData& d, const PlotContext& c) {
  f.begin("wheels.png", "Reaction wheels (truth)");
  std::vector<double> speeds, stored;
  for (const auto& r : d.truth) {
    speeds.insert(speeds.end(), r.wheel_rad_s.begin(), r.wheel_rad_s.begin() + std::max<std::size_t>(d.wheel_count, 1));
    stored.push_back(r.h_wheels_Nms);
  }
  f.multiplot(2, 1, "Reaction wheels (truth)");
  f.s << "set title 'Wheel speeds relative to the body'\n"
    << rangeHolding(speeds) << "set ylabel 'wheel speed [rad/s]'\nplot ";
  for (std::size_t i = 0; i < std::max<std::size_t>(d.wheel_count, 1); ++i) {
    f.s << (i ? ", '' " : f.dat("truth.dat")) << " using 1:" << 6 + i << " with lines title 'wheel " << i + 1 << "'";
  }
  // The capacity line only where it does not flatten the curve; else in the title.
  double h_max = 0;
  for (const auto& r : d.truth) h_max = std::max(h_max, r.h_wheels_Nms);
  const bool capacity_line = c.wheel_capacity_Nms && h_max > 0.25 * *c.wheel_capacity_Nms;
  f.s << "\nset title 'Angular momentum stored in the wheels";
  if (c.wheel_capacity_Nms && !capacity_line) f.s << " (one wheel holds " << *c.wheel_capacity_Nms << " N·m·s)";
  f.s << "'\n" << (capacity_line ? "set autoscale y\n" : rangeHolding(stored))
    << "set ylabel '|h wheels| [N·m·s]'\nplot " << f.dat("truth.dat") << " using 1:10 with lines lw 2 title '|h| stored'";
  if (capacity_line) f.s << ", " << *c.wheel_capacity_Nms << " with lines dt 2 lc rgb 'red' title 'one wheel capacity'";
  f.s << "\nunset multiplot\n";
}

void dipoleFigure(FigureScript& f, const PlotData& d, const PlotContext& c) {
  if (!d.dipole.empty()) {
    f.begin("dipole.png", "Magnetorquer dipole command (unloading controller)");
    f.multiplot(2, 1, "Magnetic unloading: dipole command and coil duty");
    f.s << "set title 'Commanded dipole, body axes'\nset ylabel 'dipole [A·m²]'\nplot " << f.dat("dipole.dat")
      << " using 1:2 with steps title 'm x', '' using 1:3 with steps title 'm y', '' using 1:4 with steps title 'm z'\n";
    if (c.max_dipole_Am2) {
      f.s << "set title 'Coil duty: |m| over the coil limit'\nset ylabel 'duty [%]'\nset yrange [0:105]\nplot "
        << f.dat("dipole.dat") << " using 1:5 with steps title 'coil x', '' using 1:6 with steps title 'coil y', '' using 1:7 with steps title 'coil z'\n";
    } else {
      f.s << "set title 'Unloading engaged'\nset ylabel 'active [0/1]'\nset yrange [-0.1:1.1]\nplot "
        << f.dat("dipole.dat") << " using 1:8 with steps title 'active'\n";
    }
    f.s << "unset multiplot\n";
  }
}

void fieldFigure(FigureScript& f, const PlotData& d) {
  f.begin("field.png", "Geomagnetic field, body axes");
  f.multiplot(2, 2, "Geomagnetic field in body axes: true, measured (magnetometer), true field seen through the "
                   "estimated attitude");
  f.s << "set key font ',10'\n";
  for (int axis_index = 0; axis_index < 3; ++axis_index) {
    const char name = static_cast<char>('x' + axis_index);
    f.s << "set title 'body " << name << "'\nset ylabel 'B " << name << " [µT]'\nplot " << f.dat("truth.dat")
      << " using 1:" << 11 + axis_index << " with lines lw 4 lc rgb '#bbbbbb' title 'true'";
    if (!d.magnetometer.empty()) f.s << ", " << f.dat("magnetometer.dat") << " using 1:" << 2 + axis_index << " with lines lc rgb '#1f77b4' title 'measured'";
    if (!d.estimate.empty()) f.s << ", " << f.dat("estimate.dat") << " using 1:" << 6 + axis_index << " with lines dt 2 lc rgb '#d62728' title 'estimated attitude'";
    f.s << "\n";
  }
  if (!d.magnetometer.empty()) {
    f.s << "set title 'Magnetometer error: measured − true'\nset ylabel 'error [nT]'\nplot " << f.dat("magnetometer.dat")
      << " using 1:5 with lines lw 0.5 title 'x', '' using 1:6 with lines lw 0.5 title 'y', '' using 1:7 with lines lw 0.5 title 'z'\n";
  }
  f.s << "unset multiplot\n";
}

void estimatorFigure(FigureScript& f, const PlotData& d) {
  if (!d.estimate.empty()) {
    f.begin("estimator_error.png", "Attitude estimation error (estimate vs truth)");
    const bool bounds = d.estimate_covariance;
    f.multiplot(bounds ? 4 : 2, 1,
                std::string("Attitude estimation error (estimate vs truth)") + (bounds ? " with the filter 3σ bounds" : ""));
    f.s << "set title 'Rotation angle between estimated and true attitude'\nset ylabel 'error angle [deg]'\nset logscale y\nplot "
      << f.dat("estimate.dat") << " using 1:2 with lines title 'error angle'\nunset logscale y\n";
    if (bounds) {
      // One panel per axis: the error against ±3σ of the filter's covariance.
      for (int axis_index = 0; axis_index < 3; ++axis_index) {
        const char name = static_cast<char>('x' + axis_index);
        const int error = 3 + axis_index, sigma = 9 + axis_index;
        // The initial uncertainty (TRIAD's sigma) would flatten the rest: the
        // range covers 95 % of the samples of |error| and 3σ.
        std::vector<double> magnitudes;
        for (const auto& r : d.estimate) {
          magnitudes.push_back(std::abs(r.error_B_deg[axis_index]));
          if (r.sigma3_B_deg) magnitudes.push_back((*r.sigma3_B_deg)[axis_index]);
        }
        const auto p95 = magnitudes.begin() + static_cast<std::ptrdiff_t>(0.95 * (magnitudes.size() - 1));
        std::nth_element(magnitudes.begin(), p95, magnitudes.end());
        const double range = std::max(*p95 * 1.3, 1e-6);
        f.s << "set title 'Small-angle error about body " << name
          << " (range: 95 % of the samples)'\nset yrange [" << -range << ":" << range
          << "]\nset ylabel 'error " << name << " [deg]'\nplot " << f.dat("estimate.dat") << " using 1:" << error
          << " with lines lc rgb '#1f77b4' title 'error', '' using 1:" << sigma
          << " with lines dt 2 lc rgb '#d62728' title '+3σ (covariance)', '' using 1:(-$" << sigma
          << ") with lines dt 2 lc rgb '#d62728' title '−3σ'\n";
      }
    } else {
      f.s << "set title 'Small-angle error per body axis (this estimator publishes no covariance)'\n"
        << "set ylabel 'error [deg]'\nplot " << f.dat("estimate.dat")
        << " using 1:3 with lines title 'about x', '' using 1:4 with lines title 'about y', '' using 1:5 with lines title 'about z'\n";
    }
    f.s << "unset multiplot\n";
  }
}

void thrusterFigure(FigureScript& f, const PlotData& d) {
  if (!d.thruster.empty()) {
    bool pulses = false;
    for (const auto& r : d.thruster) pulses |= r.pulse != 0;
    f.begin("thrusters.png", "Thruster firings (thruster sequencer)");
    f.multiplot(pulses ? 3 : 2, 1, "Thruster firings (thruster sequencer)");
    f.s << "set title 'Which thruster fired (one mark per firing step)'\nset ylabel 'thruster [-]'\n"
      << "set yrange [0.5:" << d.thruster_count + 0.5 << "]\nset ytics 1\nplot ";
    for (std::size_t i = 0; i < d.thruster_count; ++i) {
      f.s << (i ? ", '' " : f.dat("thruster.dat")) << " using 1:($" << 5 + i << " > 0 ? " << i + 1
        << " : NaN) with points pt 5 ps 0.5 title 'thruster " << i + 1 << "'";
    }
    f.s << "\nset autoscale y\nset ytics autofreq\n"
      << "set title 'On-time per firing step, summed over the thrusters'\nset ylabel 'on-time [s]'\nplot "
      << f.dat("thruster.dat") << " using 1:2 with impulses lw 2 lc rgb '#2ca02c' title 'on-time'\n";
    if (pulses) {
      f.s << "set title 'Pulses about the controlled axis: +1 / −1'\nset ylabel 'pulse [-]'\nset yrange [-1.3:1.3]\nplot "
        << f.dat("thruster.dat") << " using 1:3 with impulses lw 2 lc rgb '#1f77b4' title 'correction or braking', "
        << "'' using 1:4 with impulses lw 2 lc rgb '#d62728' title 'braking'\n";
    }
    f.s << "unset multiplot\n";
  }
}

void trackFigure(FigureScript& f, const PlotData& d) {
  if (d.track != PlotData::Track::kNone && !d.truth.empty()) {
    const bool geodetic = d.track == PlotData::Track::kGeodetic;
    f.begin("ground_track.png",
            geodetic ? "Ground track (sub-satellite point, WGS-84, truth)" : "Ground track (GMST rotation, spherical Earth)",
            false);
    bool sunlit = false, eclipsed = false;  // a dawn-dusk orbit has no eclipse: no empty series
    for (const auto& r : d.truth) (r.illumination >= 0.5 ? sunlit : eclipsed) = true;
    f.s << "set xlabel 'longitude [deg]'\nset ylabel '" << (geodetic ? "geodetic" : "geocentric")
      << " latitude [deg]'\nset xrange [-180:180]\nset yrange [-90:90]\nset rmargin -1\n"
      << "set xtics 30\nset ytics 30\nset size ratio 0.5\nset key outside bottom center horizontal box\n"
      << "plot ";
    if (sunlit) f.s << f.dat("track_sun.dat") << " with lines lw 2 lc rgb '#ff9900' title 'sunlit', ";
    if (eclipsed) f.s << f.dat("track_eclipse.dat") << " with lines lw 2 lc rgb '#1f3b73' title 'eclipse', ";
    f.s << "'-' with points pt 7 ps 2 lc rgb 'black' title 'start'\n"
      << d.truth.front().lon_deg << " " << d.truth.front().lat_deg << "\ne\n";
  }
}

/// Data files (gnuplot/*.dat) and the script that turns them into PNGs.
/// Returns the PNG names the script writes.
std::vector<std::string> writeScript(const PlotData& d, const PlotContext& c, const fs::path& out,
                                     std::size_t max_points, const fs::path& script) {
  const fs::path data = out / "gnuplot";
  fs::create_directories(data);  // before the script opens: it may live there
  const TimeAxis ta = timeAxis(d);
  writeDataFiles(d, c, data, ta, max_points);  // first: a failure leaves no script behind
  FigureScript f{std::ofstream(script), out, data, ta, {}, &d.events};
  f.s << "# Generated by flatsat plot from " << d.truth.size() << " truth samples; rerun: gnuplot "
      << script.filename().string() << "\nset encoding utf8\n"
      << "set terminal pngcairo size 1400,850 noenhanced font 'DejaVu Sans,12' linewidth 1.5\n";
  // Line types survive `reset`: every figure draws its series in these colours.
  for (std::size_t i = 0; i < std::size(kSeriesColours); ++i) {
    f.s << "set linetype " << i + 1 << " lc rgb '" << kSeriesColours[i] << "' lw 1 pt " << i + 1 << "\n";
  }
  f.s << "set linetype cycle " << std::size(kSeriesColours) << "\n";
  pointingFigure(f, d, c);
  ratesFigure(f);
  wheelsFigure(f, d, c);
  dipoleFigure(f, d, c);
  fieldFigure(f, d);
  estimatorFigure(f, d);
  thrusterFigure(f, d);
  trackFigure(f, d);
  if (!f.s.flush()) throw std::runtime_error("cannot write " + script.string());
  return f.pngs;
}

int runGnuplot(const fs::path& script) {
  const std::string program = "gnuplot";
  std::string path = script.string();
  char* argv[] = {const_cast<char*>(program.c_str()), path.data(), nullptr};
  pid_t pid = 0;
  if (const int rc = ::posix_spawnp(&pid, program.c_str(), nullptr, nullptr, argv, environ); rc != 0) {
    std::cerr << "error: cannot run gnuplot (" << std::strerror(rc)
              << "); install it: apt-get install gnuplot-nox\n";
    return 1;
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << "error: gnuplot failed on " << script.string() << "\n";
    return 1;
  }
  return 0;
}

int plot(const PlotOptions& o) {
  if (!fs::is_regular_file(o.recording)) {
    std::cerr << "error: " << o.recording << ": no such recording\n";
    return 1;
  }
  const fs::path run_dir = fs::absolute(o.recording).parent_path();
  const fs::path out = fs::absolute(o.out.empty() ? run_dir / "plots" : fs::path(o.out));
  std::string scenario = o.scenario;
  if (scenario.empty() && fs::exists(run_dir / "scenario.yaml")) scenario = (run_dir / "scenario.yaml").string();
  PlotContext context;
  try {
    context = readPlotContext(scenario);
  } catch (const std::exception& e) {
    std::cerr << "flatsat plot: " << scenario << ": " << e.what() << "; plotting without it\n";
  }
  if (scenario.empty()) {
    std::cerr << "flatsat plot: no scenario.yaml next to the recording: no limits drawn\n";
  }
  const PlotData data = readPlotData(o.recording, context);
  if (data.truth.empty()) {
    std::cerr << "error: " << o.recording << " holds no truth samples\n";
    return 1;
  }
  fs::create_directories(out);
  const fs::path script = out / "gnuplot" / "plots.gp";
  const auto pngs = writeScript(data, context, out, o.max_points, script);
  if (const int rc = runGnuplot(script); rc != 0) return rc;
  for (const auto& png : pngs) {
    if (!fs::exists(out / png) || fs::file_size(out / png) == 0) {
      std::cerr << "error: gnuplot did not write " << (out / png).string() << "\n";
      return 1;
    }
    if (o.list) std::cout << (out / png).string() << "\n";
  }
  return 0;
}

}  // namespace

int plotRecording(const std::string& recording, const std::string& out_dir, bool list) {
  PlotOptions o;
  o.recording = recording;
  o.out = out_dir;
  o.list = list;
  try {
    return plot(o);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

CLI::App* addPlotCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<PlotOptions>();
  auto* cmd = app.add_subcommand("plot", "draw a recording's review figures as PNG (gnuplot)");
  cmd->add_option("recording", options->recording, "recording.sqlite of a run")->required();
  cmd->add_option("-o,--out", options->out, "output folder (default: 'plots' next to the recording)");
  cmd->add_option("--scenario", options->scenario,
                  "the run's scenario (default: scenario.yaml next to the recording); gives the "
                  "epoch (ground track), pointing axis, wheel and coil limits");
  cmd->add_option("--max-points", options->max_points, "points per curve at most (default 20000)")
      ->check(CLI::Range(100, 10000000));
  cmd->footer(
      "Writes pointing_error, body_rates, wheels, dipole, field, estimator_error (with\n"
      "the filter's 3σ when the estimate carries its covariance), thrusters and\n"
      "ground_track .png (dipole and thrusters when recorded); the data and the\n"
      "gnuplot script stay in <out>/gnuplot (rerun: gnuplot <out>/gnuplot/plots.gp).\n"
      "Needs gnuplot (Debian: gnuplot-nox).");
  cmd->callback([options, &exit_code] { runReportingErrors(exit_code, [&] { return plot(*options); }); });
  return cmd;
}

}  // namespace flatsat::tools
