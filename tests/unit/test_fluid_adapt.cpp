// The adaptive fluid mesh (fluid.adapt, docs/fluid.md "Adaptive mesh"), on
// scenes/validation/immersed_block_adaptive.yaml: the remesh carries P1 fields exactly where they are
// linear, a fluid at rest stays hydrostatic through every remesh (so the neutrally buoyant block feels
// Archimedes' force and stays at rest), runs are the same bits on 1 and 2 threads and continue bit for bit
// from a checkpoint, and bad input is refused with the key to change.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/mesh/graded_box.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/coupling/fluid_solid_tables.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/simulation.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

Scene adaptive_scene(std::vector<std::string> overrides = {}) {
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/immersed_block_adaptive.yaml",
                    overrides);
}

RunOptions quiet() {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  return o;
}

FluidModel& fluid_of(Simulation& sim) {
  for (const auto& m : sim.world().models)
    if (m->name() == "fluid") return dynamic_cast<FluidModel&>(*m);
  throw std::runtime_error("no fluid model");
}

// P1 interpolation is exact for a linear field; the new nodes lie in the old mesh (same box). Velocity is
// checked off the walls (this field breaks the no-slip condition there, which the next step imposes),
// pressure everywhere. Tolerance:
// round-off of the barycentric coordinates, 1e-13 of the fields' size (about 10).
TEST(FluidAdapt, ARemeshCarriesLinearFieldsExactly) {
  Simulation sim(adaptive_scene(), quiet());
  FluidModel& fluid = fluid_of(sim);
  Table& nodes = sim.world().store.table(fluid::node_table);
  auto linear_u = [](const double* x, int d) {
    return d == 0 ? 1 + 2 * x[0] - x[1] : d == 1 ? 3 * x[2] : x[0] + x[1] + x[2];
  };
  auto linear_p = [](const double* x) { return 5 + 7 * x[0] - 3 * x[1] + 2 * x[2]; };
  {
    const auto x = nodes.span<double>("x");
    auto u = nodes.span<double>("velocity");
    auto p = nodes.span<double>("pressure");
    for (size_t n = 0; n < nodes.size(); ++n) {
      for (int d = 0; d < 3; ++d) u[3 * n + d] = linear_u(&x[3 * n], d);
      p[n] = linear_p(&x[3 * n]);
    }
  }
  // A different mesh of the same box: refined at a sheet instead of the block.
  GradedBoxSpec box;
  box.hi = {1, 1, 1};
  box.size_min = 0.06, box.size_max = 0.3, box.grading = 0.5;
  const std::vector<double> sheet = {0.2, 0.2, 0.3, 0.8, 0.2, 0.3, 0.8, 0.8, 0.3};
  const TetMesh mesh = generate_graded_box(box, sheet);
  const size_t before = nodes.size();
  fluid.remesh(mesh, 0.0);
  ASSERT_EQ(nodes.size(), mesh.nodes.size());
  ASSERT_NE(nodes.size(), before);
  EXPECT_EQ(fluid.mesh_revision(), 1);
  EXPECT_EQ(fluid.solver().node_count(), mesh.nodes.size());
  const auto x = nodes.span<double>("x");
  const auto u = nodes.span<double>("velocity");
  const auto p = nodes.span<double>("pressure");
  double du = 0, dp = 0;
  size_t interior = 0;
  for (size_t n = 0; n < nodes.size(); ++n) {
    dp = std::max(dp, std::abs(p[n] - linear_p(&x[3 * n])));
    bool wall = false;
    for (int d = 0; d < 3; ++d) wall = wall || x[3 * n + d] == 0.0 || x[3 * n + d] == 1.0;
    if (wall) continue;  // the next step imposes the walls' values
    ++interior;
    for (int d = 0; d < 3; ++d) du = std::max(du, std::abs(u[3 * n + d] - linear_u(&x[3 * n], d)));
  }
  EXPECT_GT(interior, 100u);
  EXPECT_LT(du, 1e-12);
  EXPECT_LT(dp, 1e-12);
}

TEST(FluidAdapt, TheMeshIsFineAtTheBlockAndCoarseAway) {
  Simulation sim(adaptive_scene(), quiet());
  const Table& tets = sim.world().store.table(fluid::tet_table);
  const auto x = sim.world().store.table(fluid::node_table).span<const double>("x");
  const auto conn = tets.span<const int32_t>("nodes");
  // Longest edges of tets whose centroid is within 0.05 m of the block [0.4, 0.6]^3, and beyond 0.35 m.
  double near_sum = 0, far_sum = 0;
  size_t near_n = 0, far_n = 0;
  for (size_t t = 0; t < tets.size(); ++t) {
    double c[3] = {0, 0, 0}, longest = 0;
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) c[d] += 0.25 * x[3 * conn[4 * t + a] + d];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        double l2 = 0;
        for (int d = 0; d < 3; ++d)
          l2 += std::pow(x[3 * conn[4 * t + a] + d] - x[3 * conn[4 * t + b] + d], 2);
        longest = std::max(longest, std::sqrt(l2));
      }
    double out2 = 0, inside = 1e9;  // distance to the block's surface
    for (int d = 0; d < 3; ++d) {
      const double o = std::max({0.4 - c[d], c[d] - 0.6, 0.0});
      out2 += o * o;
      inside = std::min(inside, std::min(c[d] - 0.4, 0.6 - c[d]));
    }
    const double dist = out2 > 0 ? std::sqrt(out2) : inside;
    if (dist < 0.05) near_sum += longest, ++near_n;
    if (dist > 0.35) far_sum += longest, ++far_n;
  }
  ASSERT_GT(near_n, 0u);
  ASSERT_GT(far_n, 0u);
  // h: 0.05 at the faces (edges up to ~2 h), at least 0.05 + 0.4 x 0.35 = 0.19 beyond 0.35 m.
  EXPECT_LT(near_sum / near_n, 0.5 * far_sum / far_n);
}

// A fluid at rest under gravity has the hydrostatic pressure, linear in z: every remesh carries it exactly,
// so the block keeps Archimedes' force, rho_f g V = 78.48 N (its weight), and stays at rest as on the fixed
// mesh (test_fluid_solid.cpp, same tolerances).
TEST(FluidAdapt, ANeutrallyBuoyantBlockStaysAtRestThroughEveryRemesh) {
  Simulation sim(adaptive_scene(), quiet());
  while (sim.step() < sim.total_steps()) sim.step_once();
  const Store& store = sim.world().store;
  EXPECT_EQ(store.table(fluid::step_table).span<const int64_t>("remeshes")[0], 4);  // 0.02 s / 0.005 s
  const auto force = store.table(coupling::state_table).span<const double>("force");
  const double archimedes = 1000.0 * 9.81 * 0.008;
  EXPECT_NEAR(force[2], archimedes, 1e-6 * archimedes);
  EXPECT_NEAR(force[0], 0.0, 1e-6 * archimedes);
  EXPECT_NEAR(force[1], 0.0, 1e-6 * archimedes);
  double speed = 0.0;
  for (double v : store.table(solid::node_table).span<const double>("v"))
    speed = std::max(speed, std::abs(v));
  EXPECT_LT(speed, 1e-9);
}

std::vector<std::string> moving() {
  return {"solid.initial_velocity=[{velocity: [0.05, 0, 0.1]}]", "solid.materials[0].density=1500"};
}

TEST(FluidAdapt, OneAndTwoThreadsGiveTheSameBits) {
  test::TempDir dir;
  const Scene scene = adaptive_scene(moving());
  const RunResult one = test::run_scene(scene, dir.path() / "t1", 1);
  const RunResult two = test::run_scene(scene, dir.path() / "t2", 2);
  ASSERT_TRUE(one.completed);
  EXPECT_EQ(one.state_hash, two.state_hash);
}

// From mid-window after a remesh (the checkpoint holds a mesh that is not the scene's first), and from
// a window's end, right after a remesh.
TEST(FluidAdapt, ARestartContinuesBitForBitOnTheCheckpointsMesh) {
  test::TempDir dir;
  const Scene scene = adaptive_scene(moving());
  const RunResult whole = test::run_scene(scene, dir.path() / "whole", 1);
  ASSERT_TRUE(whole.completed);
  const int64_t window = whole.steps / 4;  // 4 fluid steps
  for (const int64_t stop : {window + window / 2, 2 * window}) {
    const auto [first, rest] =
        test::stop_and_resume(scene, dir.path() / ("split" + std::to_string(stop)), 1, stop);
    EXPECT_FALSE(first.completed);
    ASSERT_TRUE(rest.completed);
    EXPECT_EQ(rest.state_hash, whole.state_hash) << "stopped after step " << stop;
  }
}

// The concurrent coupling remeshes at the window's end too, after the join (docs/coupling.md): the same
// bits on 1 and 2 threads, and a restart from inside a window (the fluid step already joined there)
// continues bit for bit.
TEST(FluidAdapt, TheConcurrentCouplingRemeshesBitForBit) {
  test::TempDir dir;
  std::vector<std::string> overrides = moving();
  overrides.push_back("fluid_solid.coupling=concurrent");
  const Scene scene = adaptive_scene(overrides);
  const RunResult one = test::run_scene(scene, dir.path() / "t1", 1);
  const RunResult two = test::run_scene(scene, dir.path() / "t2", 2);
  ASSERT_TRUE(one.completed);
  EXPECT_EQ(one.state_hash, two.state_hash);
  const auto [first, rest] =
      test::stop_and_resume(scene, dir.path() / "split", 2, one.steps / 4 + one.steps / 8);
  ASSERT_TRUE(rest.completed);
  EXPECT_EQ(rest.state_hash, one.state_hash);
}

TEST(FluidAdapt, BadInputNamesTheKey) {
  auto message = [](std::vector<std::string> overrides) {
    try {
      adaptive_scene(std::move(overrides));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string cells = message({"fluid.mesh.generate.cells=[4, 4, 4]"});
  EXPECT_NE(cells.find("fluid.mesh"), std::string::npos) << cells;
  EXPECT_NE(cells.find("with fluid.adapt"), std::string::npos) << cells;
  const std::string surfaces = message({"fluid.adapt.surfaces=[cracks]"});
  EXPECT_NE(surfaces.find("fluid.adapt.surfaces"), std::string::npos) << surfaces;
  EXPECT_NE(surfaces.find("boundary, notch and fracture"), std::string::npos) << surfaces;
  const std::string none = message({"fluid.adapt.surfaces=[]"});
  EXPECT_NE(none.find("fluid.adapt.surfaces: expected a list of at least one"), std::string::npos) << none;
  const std::string interval = message({"fluid.adapt.interval=-1"});
  EXPECT_NE(interval.find("fluid.adapt.interval"), std::string::npos) << interval;
}

}  // namespace
}  // namespace rift
