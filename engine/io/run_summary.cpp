#include "engine/io/run_summary.hpp"

#include <cmath>
#include <string>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"

namespace rift {

void RunSummary::set(std::string_view dotted_path, nlohmann::json value) {
  nlohmann::json* node = &root_;
  size_t start = 0;
  while (true) {
    const size_t dot = dotted_path.find('.', start);
    const std::string key(
        dotted_path.substr(start, dot == std::string_view::npos ? dotted_path.npos : dot - start));
    if (key.empty()) throw Error("run summary key '" + std::string(dotted_path) + "' has an empty segment");
    if (!node->is_object())
      throw Error(
          "run summary key '" + std::string(dotted_path) + "': " +
          (start == 0 ? std::string("the root") : "'" + std::string(dotted_path.substr(0, start - 1)) + "'") +
          " holds a " + node->type_name() + ", not an object");
    if (dot == std::string_view::npos) {
      (*node)[key] = std::move(value);
      return;
    }
    nlohmann::json& child = (*node)[key];
    if (child.is_null()) child = nlohmann::json::object();
    node = &child;
    start = dot + 1;
  }
}

namespace {

// JSON has no infinity or NaN (nlohmann writes them as null, which reads as "missing"): each is written
// as the string "inf", "-inf" or "nan" instead, so a reader sees what the value was (a step without limit,
// an energy that overflowed before a guard stopped the run) and no number that is not one.
nlohmann::json with_non_finite_as_strings(const nlohmann::json& j) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return j;
  }
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto it = j.begin(); it != j.end(); ++it) out[it.key()] = with_non_finite_as_strings(it.value());
    return out;
  }
  if (j.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : j) out.push_back(with_non_finite_as_strings(v));
    return out;
  }
  return j;
}

}  // namespace

void RunSummary::write(const std::filesystem::path& file) const {
  write_text_atomic(
      file,
      with_non_finite_as_strings(root_).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace rift
