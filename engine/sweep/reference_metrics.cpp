#include "engine/sweep/reference_metrics.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

namespace rift {

namespace {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};

Csv read_csv(const std::filesystem::path& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return csv;
  std::stringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');) csv.header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::strtod(cell.c_str(), nullptr));
    if (row.size() == csv.header.size()) csv.rows.push_back(std::move(row));
  }
  return csv;
}

std::optional<double> reduce_column(const Csv& csv, size_t column, ReferenceMetricSpec::Reduce how) {
  using Reduce = ReferenceMetricSpec::Reduce;
  if (csv.rows.empty()) return std::nullopt;
  if (how == Reduce::final) return csv.rows.back()[column];
  double best = how == Reduce::min ? INFINITY : -INFINITY;
  for (const auto& r : csv.rows) {
    const double v = how == Reduce::max_abs ? std::abs(r[column]) : r[column];
    best = how == Reduce::min ? std::min(best, v) : std::max(best, v);
  }
  return best;
}

std::string list_of(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<MetricValue> read_reference_metrics(const std::vector<ReferenceMetricSpec>& metrics,
                                                const std::filesystem::path& run_dir) {
  std::vector<MetricValue> out;
  if (metrics.empty()) return out;
  const Csv csv = read_csv(run_dir / "timeseries.csv");
  nlohmann::json summary;
  if (std::ifstream in(run_dir / "summary.json"); in) summary = nlohmann::json::parse(in, nullptr, false);
  for (const auto& m : metrics) {
    MetricValue v{m.name, std::nullopt, m.value, ""};
    if (!m.series.empty()) {
      size_t column = 0;
      while (column < csv.header.size() && csv.header[column] != m.series) ++column;
      if (column == csv.header.size())
        v.problem = "no column '" + m.series + "' in timeseries.csv; its columns are: " + list_of(csv.header);
      else if (auto r = reduce_column(csv, column, m.reduce))
        v.value = m.factor * *r;
      else
        v.problem = "timeseries.csv has no rows";
    } else {
      const nlohmann::json* node = &summary;
      std::stringstream path(m.summary);
      for (std::string part; std::getline(path, part, '.') && node;)
        node = node->is_object() && node->contains(part) ? &(*node)[part] : nullptr;
      if (node && node->is_number())
        v.value = m.factor * node->get<double>();
      else
        v.problem = "summary.json has no number at '" + m.summary + "'";
    }
    out.push_back(std::move(v));
  }
  return out;
}

double relative_error(double value, double reference) {
  return reference == 0.0 ? std::abs(value) : std::abs(value - reference) / std::abs(reference);
}

}  // namespace rift
