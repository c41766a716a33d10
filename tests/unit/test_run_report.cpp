// The console's end-of-run report (engine/run_report.hpp) from a summary.json: the physics of each model
// present, nothing for the absent ones, and the wall time with the meshing in it.
#include <gtest/gtest.h>

#include "engine/run_report.hpp"

namespace rift {
namespace {

TEST(RunReport, SaysWhatThePhysicsDidAndTheWholeWallTime) {
  const auto summary = nlohmann::json::parse(R"({
    "wall_seconds": 66.0, "mesh": {"seconds": 8.5},
    "metrics": {"solid": {"joints": 10, "broken_joints": 3, "fractures": {"tensile": 2, "shear": 1, "initial": 0},
                          "energy": {"external_work": 2.0, "kinetic": 0.5, "elastic": 1.0, "joint_stored": 0.1,
                                     "fracture": 0.3, "friction": 0.0, "damping": 0.08, "balance_error": 0.02}},
                "mesh_conversion": {"fragments": 2, "fracture_surfaces": 1, "fracture_triangles": 6}}})");
  const std::string report = run_report(summary);
  EXPECT_NE(report.find("3 of 10 joints broken (2 tensile, 1 shear; 0 cut at set-up)"), std::string::npos)
      << report;
  EXPECT_NE(report.find("balance error 0.02 (1 % of the work)"), std::string::npos) << report;
  EXPECT_NE(report.find("2 fragments, 1 fracture surfaces"), std::string::npos) << report;
  EXPECT_NE(report.find("wall time: 74.5 s (meshing 8.5 s, the run 66 s)"), std::string::npos) << report;
  EXPECT_EQ(report.find("fluid"), std::string::npos) << report;
  EXPECT_EQ(report.find("fracture flow"), std::string::npos) << report;
}

TEST(RunReport, AnEmptySummaryGivesNoPhysics) {
  EXPECT_EQ(run_report(nlohmann::json::object()), "");
}

}  // namespace
}  // namespace rift
