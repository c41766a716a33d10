#pragma once
// timeseries.csv: one row per recorded step, "step,time,<metric>...", every value with 17 significant
// digits so that it reads back to the same double. A restarted run reads the rows up to its restart step
// back, so the file it rewrites continues the interrupted run's series bit for bit.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rift {

std::string format_time_series(const std::vector<std::string>& metric_names,
                               const std::vector<std::vector<double>>& rows);

// The rows whose step is at most `last_step`; none when the file does not exist. Every line is
// checked, also those after `last_step`: a field that is no number (or out of a double's range) or a
// row with another number of fields than the header throws rift::Error naming the file, the line and
// the field. "nan" and "inf" are numbers here, since a metric may be one.
std::vector<std::vector<double>> read_time_series(const std::filesystem::path& file, int64_t last_step);

}  // namespace rift
