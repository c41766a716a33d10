#pragma once
// `rift plot RUN_DIR`: PNGs of a run's time series (energies and the balance error, reactions, fracture,
// fracture flow, fluid), drawn by matplotlib from timeseries.csv into RUN_DIR/plots (or `out`).
#include <filesystem>
#include <string>
#include <vector>

namespace rift {

struct RunPlotResult {
  std::vector<std::filesystem::path> pictures;  // written, one per family of columns the run has
  std::string problem;                          // why nothing was drawn; empty on success
};

RunPlotResult plot_run(const std::filesystem::path& run_dir, const std::filesystem::path& out_dir = {});

}  // namespace rift
