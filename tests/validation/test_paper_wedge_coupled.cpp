// The paper's wedge coupled for real (scenes/examples/guo2015_wedge.yaml, fluid_solid.network_inlet): the
// fracture-flow network's well, the notch, takes the surrounding fluid's pressure at the notch's mouth
// after every fluid step, and what the network takes in leaves the surrounding fluid there as a sink,
// both spread over the fluid cells of the mouth (fluid_solid.network_inlet_extent).
// On the coarse preset (4 - 8 mm cells), for the first 25 us of the settling at 15 MPa:
//  - the two sides' masses agree: at every window's end the mass the surrounding fluid has given up is the
//    network's intake, bit for bit, and the sink the fluid step takes integrates to that window's intake
//    over the fluid step (1e-12: a sum of one term per cell);
//  - the well holds the sampled pressure (exactly, between exchanges);
//  - the sampled pressure is the inlet's within 0.5 MPa (the bound) while the block settles;
//  - a run stopped inside a window, with a sink pending in the fluid and the well holding a sampled
//    pressure, continues from its checkpoint bit for bit;
//  - a box around the inlet that holds no fluid cell's centre is refused, with the box and the remedy;
//  - the cells of the rock's box (the notch's among them) are the network's: the surrounding fluid's
//    continuity weight is 0 there, and 1 - alpha in the inlet's cells and in front of the rock.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/fracture_flow_support.hpp"
#include "tests/validation/paper_wedge_support.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift {
namespace {

using validation::flow_of;
using validation::metric;
using validation::run_watching;

FluidModel& fluid_of(Simulation& sim) {
  for (auto& m : sim.world().models)
    if (auto* f = dynamic_cast<FluidModel*>(m.get())) return *f;
  throw std::runtime_error("the scene has no fluid");
}

Model& coupling_of(Simulation& sim) {
  for (auto& m : sim.world().models)
    if (m->name() == "fluid_solid") return *m;
  throw std::runtime_error("the scene has no fluid_solid coupling");
}

// The coarse preset, mass-scaled, for the first `end` seconds.
Scene coarse_wedge(const std::string& end, std::vector<std::string> more = {}) {
  more.push_back("time.end=" + end);
  return validation::coupled_wedge_coarse(more);
}

TEST(PaperWedgeCoupled, TheNetworkTakesTheSurroundingFluidsPressureAndItsMass) {
  const double kInlet = 1.5e7, kRho = 1000.0;
  const Scene scene = coarse_wedge("2.5e-5");
  const double fluid_dt = scene.fluid->dt;
  size_t windows = 0, held_steps = 0, mass_mismatches = 0;
  int64_t remeshes_before = 0;
  double worst_sink_error = 0.0, worst_well_gap = 0.0, worst_inlet_gap = 0.0, sink_before = 0.0, intake = 0.0;
  const RunResult r = run_watching(scene, 2, [&](Simulation& sim) {
    std::vector<std::pair<std::string, double>> row, flow;
    coupling_of(sim).metrics(sim.time(), row);
    flow_of(sim).metrics(sim.time(), flow);
    const double inlet = metric(row, "fluid_solid_inlet_pressure");
    const double sink = metric(row, "fluid_solid_inlet_sink_mass");
    intake = kRho * metric(flow, "flow_injected_volume");
    worst_inlet_gap = std::max(worst_inlet_gap, std::abs(inlet - kInlet));
    if (sim.step() == 0) return;
    const bool window_end = std::abs(std::remainder(sim.time(), fluid_dt)) < 1e-3 * sim.dt();
    if (!window_end) {  // the well held the sampled pressure over this step
      worst_well_gap = std::max(worst_well_gap, std::abs(metric(flow, "flow_well_pressure") - inlet));
      ++held_steps;
      return;
    }
    ++windows;
    // Mass between the network and the fluid to 1e-12 relative (the bound): the sink is summed
    // window by window, the intake is the network's running total, so they may differ in the last bit.
    if (std::abs(sink - intake) > 1e-12 * std::abs(intake)) {
      ++mass_mismatches;
      std::printf("mismatch at %g: sink %.17g intake %.17g\n", sim.time(), sink, intake);
    }
    // A remesh after the window (fluid.adapt) hands the new mesh the solid's state again, with no intake
    // left for the next window: the sink the step took is then no longer in the solver to read.
    const auto remeshes = sim.world().store.table(fluid::step_table).span<const int64_t>("remeshes")[0];
    const bool remeshed = remeshes != remeshes_before;
    remeshes_before = remeshes;
    if (remeshed) {
      sink_before = sink;
      return;
    }
    // What the fluid step took from the cell of the inlet: sum_K q_K |K| fluid.dt, against the window's
    // intake over rho.
    fluid::FluidSolver& solver = fluid_of(sim).solver();
    const auto q = solver.volume_source();
    const auto v = solver.volumes();
    double taken = 0.0;
    for (size_t k = 0; k < q.size(); ++k) taken -= q[k] * v[k] * fluid_dt;
    const double expected = (sink - sink_before) / kRho;
    if (expected != 0.0) worst_sink_error = std::max(worst_sink_error, std::abs(taken / expected - 1.0));
    sink_before = sink;
  });
  std::printf(
      "%zu windows, %zu held steps; intake %.4g kg; sink integral error %.2g; well - sampled %.3g Pa; "
      "sampled - inlet up to %.4g MPa\n",
      windows, held_steps, intake, worst_sink_error, worst_well_gap, worst_inlet_gap * 1e-6);
  EXPECT_TRUE(r.completed);
  EXPECT_EQ(windows, 10u);
  EXPECT_GT(intake, 0.0);  // the notch opens as the block settles: the network draws fluid
  EXPECT_EQ(mass_mismatches, 0u);
  EXPECT_LT(worst_sink_error, 1e-12);
  EXPECT_EQ(worst_well_gap, 0.0);
  EXPECT_LT(worst_inlet_gap, 0.5e6);
}

// Stopped in the middle of the fourth window, when the network has drawn fluid and the sink of that
// intake is in the fluid step under way, then continued: the same bits as the run that did not stop.
TEST(PaperWedgeCoupled, ARestartInsideAWindowContinuesBitForBit) {
  test::TempDir dir;
  const Scene scene = coarse_wedge("1.25e-5");
  const RunResult whole = test::run_scene(scene, dir.path() / "whole", 2);
  ASSERT_TRUE(whole.completed);
  const int64_t per_window = whole.steps / 5;
  const auto [first, rest] =
      test::stop_and_resume(scene, dir.path() / "split", 2, 3 * per_window + per_window / 2);
  EXPECT_FALSE(first.completed);
  ASSERT_TRUE(rest.completed);
  EXPECT_EQ(rest.steps, whole.steps);
  EXPECT_EQ(rest.state_hash, whole.state_hash);
}

// A box of 0.1 mm around a point of the fluid: smaller than any cell, it holds no cell's centre.
TEST(PaperWedgeCoupled, AnInletBoxWithoutAFluidCellIsRefused) {
  const Scene scene = coarse_wedge("2.5e-6", {"fluid_solid.network_inlet_extent=[1.0e-4, 1.0e-4, 1.0e-4]"});
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  try {
    Simulation sim(scene, o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("network_inlet_extent [0.0001, 0.0001, 0.0001]"), std::string::npos) << what;
    EXPECT_NE(what.find("no fluid cell has its centre in the box"), std::string::npos) << what;
    EXPECT_NE(what.find("make the box larger"), std::string::npos) << what;
  }
}

// At t = 0, after the first exchange: which cells the network owns, and the continuity's weight the
// fluid's solver then holds in them.
TEST(PaperWedgeCoupled, TheNotchsCellsAreTheNetworksAndHoldNoContinuity) {
  const Scene scene = coarse_wedge("2.5e-6");
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  Simulation sim(scene, o);
  fluid::FluidSolver& solver = fluid_of(sim).solver();
  const Table& tets = sim.world().store.table(fluid::tet_table);
  const auto owned = tets.span<const double>("network_cell");
  const auto alpha = tets.span<const double>("solid_fraction");
  const auto weight = solver.continuity_weight();
  const auto x = solver.nodes();
  const auto nodes = solver.tets();
  const double rock[3] = {0.049, 0.1, 0.05};
  const auto& inlet = *scene.fluid_solid->network_inlet;
  const auto& extent = scene.fluid_solid->network_inlet_extent;
  size_t in_rock = 0, in_notch = 0, in_inlet = 0, in_front = 0, wrong = 0;
  for (size_t k = 0; k < owned.size(); ++k) {
    double c[3] = {0, 0, 0};
    for (size_t a = 0; a < 4; ++a)
      for (size_t d = 0; d < 3; ++d) c[d] += 0.25 * x[3 * size_t(nodes[4 * k + a]) + d];
    bool rock_box = true, inlet_box = true;
    for (size_t d = 0; d < 3; ++d) {
      rock_box = rock_box && c[d] >= 0.0 && c[d] <= rock[d];
      inlet_box = inlet_box && std::abs(c[d] - inlet[d]) <= 0.5 * extent[d];
    }
    if (inlet_box) {
      ++in_inlet;
      wrong += owned[k] != 0.0 || weight[k] != 1.0 - alpha[k];
    } else if (rock_box) {
      ++in_rock;
      in_notch += alpha[k] < 0.9;  // the notch's cells: mostly its fluid
      wrong += owned[k] != 1.0 || weight[k] != 0.0;
    } else if (c[0] < 0.0 && alpha[k] == 0.0) {
      ++in_front;
      wrong += owned[k] != 0.0 || weight[k] != 1.0;
    }
  }
  std::printf("%zu cells in the rock's box (%zu of them the notch's), %zu the inlet's, %zu in front\n",
              in_rock, in_notch, in_inlet, in_front);
  EXPECT_GT(in_notch, 0u);
  EXPECT_GT(in_inlet, 0u);
  EXPECT_GT(in_front, 0u);
  EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace rift
