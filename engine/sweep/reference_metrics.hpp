#pragma once
// The scene's error metrics (`reference` section, docs/scene-format.md) read back from a finished run's
// folder: a timeseries.csv column reduced over the run, or a summary.json value, times a factor.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"

namespace rift {

struct MetricValue {
  std::string name;
  std::optional<double> value;      // nullopt when it could not be read (see problem)
  std::optional<double> reference;  // the scene's analytic value, if it gives one
  std::string problem;              // why value is missing: the column or path and what exists
};

std::vector<MetricValue> read_reference_metrics(const std::vector<ReferenceMetricSpec>& metrics,
                                                const std::filesystem::path& run_dir);

// |value - reference| / |reference| (|value| when the reference is 0).
double relative_error(double value, double reference);

}  // namespace rift
