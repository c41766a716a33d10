// rift plot (engine/plot/run_plot.hpp) on a made-up timeseries.csv: one PNG per family of columns the
// run has (and none for the families it lacks), a folder without a run refused with a reason. Skipped
// without a python3 that has matplotlib.
#include <gtest/gtest.h>

#include <fstream>

#include "engine/core/spawn.hpp"
#include "engine/plot/run_plot.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

TEST(RunPlot, OnePicturePerFamilyOfSeries) {
  if (python_with("matplotlib").empty()) GTEST_SKIP() << "no python3 with matplotlib: rift plot not tested";
  test::TempDir dir;
  {
    std::ofstream csv(dir / "timeseries.csv");
    csv << "step,time,solid_kinetic_energy,solid_external_work,solid_energy_balance_error,solid_broken_"
           "joints,"
           "solid_reaction_base_z,flow_well_pressure,probe_tip_0,probe_tip_1,probe_mouth\n";
    for (int i = 0; i <= 20; ++i)
      csv << i << "," << i * 1e-5 << "," << 0.1 * i << "," << 0.2 * i << "," << 1e-9 * i << "," << i / 5
          << "," << -10.0 * i << "," << 1e6 + 1e4 * i << "," << i << "," << 2 * i << "," << 1.5e7 << "\n";
  }
  const RunPlotResult r = plot_run(dir.path());
  ASSERT_TRUE(r.problem.empty()) << r.problem;
  std::vector<std::string> names;
  for (const auto& p : r.pictures) {
    names.push_back(p.filename().string());
    EXPECT_TRUE(fs::is_regular_file(p)) << p;
    EXPECT_GT(fs::file_size(p), 1000u) << p;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"energy.png", "loads.png", "fracture.png", "fracture_flow.png",
                                             "probes.png"}));
  EXPECT_EQ(r.pictures[0].parent_path(), dir / "plots");
}

TEST(RunPlot, AFolderWithoutARunIsRefused) {
  test::TempDir dir;
  const RunPlotResult r = plot_run(dir.path());
  EXPECT_TRUE(r.pictures.empty());
  EXPECT_NE(r.problem.find("timeseries.csv"), std::string::npos) << r.problem;
}

}  // namespace
}  // namespace rift
