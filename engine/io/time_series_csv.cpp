#include "engine/io/time_series_csv.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>

#include "engine/core/error.hpp"

namespace rift {
namespace {

// Every ',' separates two fields, so "1,2," has three (the last empty) and an empty line has one.
std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  for (char c : line)
    if (c == ',')
      fields.emplace_back();
    else
      fields.back() += c;
  return fields;
}

}  // namespace

std::string format_time_series(const std::vector<std::string>& metric_names,
                               const std::vector<std::vector<double>>& rows) {
  std::string csv = "step,time";
  for (const auto& n : metric_names) csv += "," + n;
  csv += "\n";
  for (const auto& r : rows) {
    for (size_t i = 0; i < r.size(); ++i) csv += fmt::format("{}{:.17g}", i ? "," : "", r[i]);
    csv += "\n";
  }
  return csv;
}

std::vector<std::vector<double>> read_time_series(const std::filesystem::path& file, int64_t last_step) {
  std::vector<std::vector<double>> rows;
  std::error_code ec;
  if (!std::filesystem::exists(file, ec) && !ec) return rows;
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in) throw Error("cannot read " + name + ": " + std::strerror(errno));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_fields(line);
  if (header.size() < 2 || header[0] != "step" || header[1] != "time")
    throw Error(fmt::format("{}:1: expected the header 'step,time,...', found '{}'", name, line));
  for (size_t number = 2; std::getline(in, line); ++number) {
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size())
      throw Error(fmt::format("{}:{}: expected {} fields as in the header, found {} (a cut or damaged row)",
                              name, number, header.size(), fields.size()));
    std::vector<double> values(fields.size());
    for (size_t k = 0; k < fields.size(); ++k) {
      const std::string& f = fields[k];
      const auto [end, parse] = std::from_chars(f.data(), f.data() + f.size(), values[k]);
      if (parse == std::errc() && end == f.data() + f.size()) continue;
      throw Error(fmt::format(
          "{}:{}: field {} ({}): expected a number, found '{}'{}", name, number, k + 1, header[k], f,
          parse == std::errc::result_out_of_range ? ", which is out of range of a double" : ""));
    }
    if (values[0] <= static_cast<double>(last_step)) rows.push_back(std::move(values));
  }
  if (in.bad()) throw Error("cannot read " + name + ": " + std::strerror(errno));
  return rows;
}

}  // namespace rift
