#pragma once
// The machine-readable account of a run (run_summary.json): scene, build, timings, final state,
// warnings. Systems fill it through dotted paths; it is written atomically so a reader never sees a
// half-written file.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

namespace rift {

class RunSummary {
 public:
  nlohmann::json& root() { return root_; }
  const nlohmann::json& root() const { return root_; }

  // set("timing.solid.seconds", 1.5) creates the objects "timing" and "solid" as needed. Throws
  // rift::Error when a level on the way already holds a non-object value or a segment is empty.
  void set(std::string_view dotted_path, nlohmann::json value);

  // Pretty-printed (2-space indent), atomic. Invalid UTF-8 in strings is replaced, not fatal; infinities
  // and NaN are written as the strings "inf", "-inf" and "nan" (JSON has no such numbers).
  void write(const std::filesystem::path& file) const;

 private:
  nlohmann::json root_ = nlohmann::json::object();
};

}  // namespace rift
