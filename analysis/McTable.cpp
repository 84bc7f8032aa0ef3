// SPDX-License-Identifier: Apache-2.0
#include "analysis/McTable.hpp"
#include "analysis/Quantile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace flatsat::analysis {

namespace {

bool numeric(const nlohmann::ordered_json& value) { return value.is_number() && !value.is_boolean(); }

}  // namespace

McStats mcStats(std::vector<double> values) {
  McStats s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  double sum = 0;
  for (const double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  double squares = 0;
  for (const double v : values) squares += (v - s.mean) * (v - s.mean);
  s.std = values.size() > 1 ? std::sqrt(squares / static_cast<double>(values.size() - 1)) : 0.0;
  s.min = values.front();
  s.max = values.back();
  s.p50 = nearestRank(values, 0.50);
  s.p95 = nearestRank(values, 0.95);
  return s;
}

std::vector<std::string> mcNumericKeys(const std::vector<McRun>& runs) {
  std::vector<std::string> keys;
  for (const auto& run : runs) {
    if (!run.summary.is_object()) continue;
    for (const auto& [key, value] : run.summary.items()) {
      if (numeric(value) && std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  return keys;
}

std::string mcCsv(const std::vector<McRun>& runs, const std::vector<std::string>& keys) {
  std::ostringstream csv;
  csv << "run,seed,exit_code,recording_sha256";
  for (const auto& key : keys) csv << ',' << key;
  csv << '\n';
  for (const auto& run : runs) {
    const bool ok = run.summary.is_object();
    csv << run.index << ',' << run.seed << ',' << (run.exit_code >= 0 ? std::to_string(run.exit_code) : "") << ','
        << (ok ? run.summary.value("recording_sha256", "") : "");
    for (const auto& key : keys) {
      csv << ',';
      // dump() writes a double with the digits that read back to the same value.
      if (ok && run.summary.contains(key) && numeric(run.summary[key])) csv << run.summary[key].dump();
    }
    csv << '\n';
  }
  return csv.str();
}

nlohmann::ordered_json mcSummary(const std::string& scenario, const std::vector<McRun>& runs,
                                 const std::vector<std::string>& keys) {
  nlohmann::ordered_json out;
  out["scenario"] = scenario;
  out["runs"] = runs.size();
  nlohmann::ordered_json failed = nlohmann::ordered_json::array();
  for (const auto& run : runs) {
    if (!run.summary.is_object()) {
      failed.push_back({{"run", run.index},
                        {"seed", run.seed},
                        {"exit_code", run.exit_code >= 0 ? nlohmann::ordered_json(run.exit_code) : nullptr},
                        {"reason", run.failure},
                        {"log", run.log}});
    }
  }
  out["succeeded"] = runs.size() - failed.size();
  out["failed"] = failed.size();
  out["failed_runs"] = failed;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  for (const auto& key : keys) {
    std::vector<double> values;
    for (const auto& run : runs) {
      if (run.summary.is_object() && run.summary.contains(key) && numeric(run.summary[key])) {
        values.push_back(run.summary[key].get<double>());
      }
    }
    const McStats s = mcStats(values);
    metrics[key] = {{"count", s.count}, {"mean", s.mean}, {"std", s.std}, {"min", s.min},
                    {"max", s.max},     {"p50", s.p50},   {"p95", s.p95}};
  }
  out["metrics"] = metrics;
  return out;
}

std::string mcTable(const nlohmann::ordered_json& summary) {
  std::ostringstream out;
  std::size_t width = 3;
  for (const auto& [key, stats] : summary["metrics"].items()) width = std::max(width, key.size());
  char line[256];
  std::snprintf(line, sizeof line, "  %-*s %12s %12s %12s %12s %12s %12s\n", static_cast<int>(width), "key",
                "mean", "std", "min", "p50", "p95", "max");
  out << line;
  for (const auto& [key, s] : summary["metrics"].items()) {
    std::snprintf(line, sizeof line, "  %-*s %12.6g %12.6g %12.6g %12.6g %12.6g %12.6g\n",
                  static_cast<int>(width), key.c_str(), s["mean"].get<double>(), s["std"].get<double>(),
                  s["min"].get<double>(), s["p50"].get<double>(), s["p95"].get<double>(),
                  s["max"].get<double>());
    out << line;
  }
  return out.str();
}

}  // namespace flatsat::analysis
