// The fluid-solid exchange (kernels/fluid_solid_exchange.hpp, systems/coupling): kernel identities that
// hold to round-off whatever the meshes (Newton's third law between the fluid's absorption and the
// solid's penalty force, Archimedes' force of a fluid at rest, the solid velocity of a rigid translation,
// conservation of the force through the gather onto the nodes), then runs of
// scenes/validation/immersed_block.yaml: a neutrally buoyant block stays at rest, 1 and 2 threads give
// the same bits, a restart from mid-window continues bit for bit, and bad coupling input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/mesh/structured_box.hpp"
#include "engine/scene/load_scene.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/fluid_solid_exchange.hpp"
#include "kernels/tet_intersection.hpp"
#include "systems/coupling/fluid_solid_tables.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/simulation.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

using namespace kernels;

struct FlatMesh {
  std::vector<double> x;
  std::vector<int32_t> tets;
  size_t num_tets() const { return tets.size() / 4; }
};

// A structured box, optionally rotated about a tilted axis and shifted (so its faces cut the other mesh
// at arbitrary angles).
FlatMesh box_mesh(std::array<double, 3> lo, std::array<double, 3> hi, std::array<int, 3> cells, double angle,
                  std::array<double, 3> shift = {0, 0, 0}) {
  const TetMesh m = structured_box({lo, hi, cells});
  FlatMesh f;
  const double c = std::cos(angle), s = std::sin(angle);
  const double centre[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  for (const auto& p : m.nodes) {
    const double q[3] = {p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]};
    // about z, then about x: a rotation no face of the other (axis-aligned) mesh shares
    const double r1[3] = {c * q[0] - s * q[1], s * q[0] + c * q[1], q[2]};
    const double r2[3] = {r1[0], c * r1[1] - s * r1[2], s * r1[1] + c * r1[2]};
    for (int d = 0; d < 3; ++d) f.x.push_back(r2[d] + centre[d] + shift[d]);
  }
  for (const auto& t : m.tets) f.tets.insert(f.tets.end(), t.begin(), t.end());
  return f;
}

double total_volume(const FlatMesh& m) {
  double v = 0.0;
  for (size_t t = 0; t < m.num_tets(); ++t) {
    double c[4][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) c[a][d] = m.x[3 * static_cast<size_t>(m.tets[4 * t + a]) + d];
    v += tet_volume(c);
  }
  return v;
}

// The solid (a tilted block) inside the fluid box, with the pairs, overlaps and cells of one exchange.
struct Exchange {
  FlatMesh fluid = box_mesh({0, 0, 0}, {1, 1, 1}, {6, 6, 6}, 0.0);
  FlatMesh solid = box_mesh({0.3, 0.3, 0.3}, {0.7, 0.65, 0.6}, {3, 2, 2}, 0.4);
  std::vector<double> fluid_volume, solid_v, solid_theta, volume, solid_volume, fraction, target, sigma,
      weight, dilatation;
  std::vector<int64_t> first;
  CouplingBroadPhaseWorkspace ws;
  double rho = 1000.0, beta = 1.0, dt = 0.01;

  explicit Exchange(std::array<double, 3> solid_velocity = {0, 0, 0}, bool random_velocity = true) {
    const size_t nf = fluid.num_tets(), ns = solid.num_tets();
    for (size_t t = 0; t < nf; ++t) {
      double c[4][3];
      for (int a = 0; a < 4; ++a)
        for (int d = 0; d < 3; ++d) c[a][d] = fluid.x[3 * static_cast<size_t>(fluid.tets[4 * t + a]) + d];
      fluid_volume.push_back(tet_volume(c));
    }
    std::vector<int32_t> fid(nf), sid(ns);
    std::iota(fid.begin(), fid.end(), 0);
    std::iota(sid.begin(), sid.end(), 0);
    std::vector<double> flo(3 * nf), fhi(3 * nf), slo(3 * ns), shi(3 * ns);
    tet_bounding_boxes(fluid.x, fluid.tets, fid, flo, fhi, 0, nf);
    tet_bounding_boxes(solid.x, solid.tets, sid, slo, shi, 0, ns);
    coupling_broad_phase({flo, fhi, slo, shi, 0.0}, ws);
    volume.resize(ws.pairs.size());
    overlap_volumes({fluid.x, fluid.tets, solid.x, solid.tets, ws.pairs, volume}, 0, ws.pairs.size());
    first.resize(nf + 1);
    pair_ranges(ws.pairs, first);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> node_v(solid.x.size());
    for (size_t i = 0; i < node_v.size(); ++i) node_v[i] = random_velocity ? u(rng) : solid_velocity[i % 3];
    solid_v.resize(3 * ns);
    tet_mean_vectors(node_v, solid.tets, solid_v, 0, ns);
    // The solid's mean rate of volume change over a window of length dt in which it moved by node_v dt.
    solid_theta.resize(ns);
    std::vector<double> volume_prev(ns), moved(solid.x.size());
    for (size_t i = 0; i < moved.size(); ++i) moved[i] = solid.x[i] + dt * node_v[i];
    tet_volume_rates(solid.x, solid.tets, dt, volume_prev, solid_theta, 0, ns);
    tet_volume_rates(moved, solid.tets, dt, volume_prev, solid_theta, 0, ns);
    dilatation.resize(nf);
    solid_volume.resize(nf);
    fraction.resize(nf);
    target.resize(3 * nf);
    sigma.resize(nf);
    weight.resize(nf);
    solid_to_fluid_cells({rho, beta, dt, fluid_volume, ws.pairs, first, volume, solid_v, solid_theta,
                          solid_volume, fraction, target, sigma, weight, dilatation},
                         0, nf);
  }
};

TEST(FluidSolidExchange, SolidVolumeIsConservedOnTheFluidMesh) {
  Exchange e;
  const double covered = std::accumulate(e.solid_volume.begin(), e.solid_volume.end(), 0.0);
  EXPECT_NEAR(covered, total_volume(e.solid), 1e-12 * total_volume(e.solid));
  for (double a : e.fraction) {
    EXPECT_GE(a, 0.0);
    EXPECT_LE(a, 1.0);
  }
}

TEST(FluidSolidExchange, VolumeRateIsThatOfTheMotion) {
  // x -> (1 + e dt) R x (a uniform stretch and a rigid rotation over the window dt): every tet's volume
  // grows by (1 + e dt)^3, so theta = ((1 + e dt)^3 - 1) / ((1 + e dt)^3 dt), exactly.
  const FlatMesh m = box_mesh({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0.3);
  const double e = 0.7, dt = 0.01, c = std::cos(0.4), s = std::sin(0.4), g = 1 + e * dt;
  std::vector<double> moved(m.x.size());
  for (size_t n = 0; n < m.x.size() / 3; ++n) {
    const double* x = &m.x[3 * n];
    moved[3 * n + 0] = g * (c * x[0] - s * x[1]);
    moved[3 * n + 1] = g * (s * x[0] + c * x[1]);
    moved[3 * n + 2] = g * x[2];
  }
  std::vector<double> volume_prev(m.num_tets()), theta(m.num_tets());
  tet_volume_rates(m.x, m.tets, dt, volume_prev, theta, 0, theta.size());
  tet_volume_rates(moved, m.tets, dt, volume_prev, theta, 0, theta.size());
  const double expected = (g * g * g - 1) / (g * g * g * dt);
  for (double t : theta) EXPECT_NEAR(t, expected, 1e-9 * expected);
}

TEST(FluidSolidExchange, TheSolidsVolumeRateIsConservedOnTheFluidMesh) {
  // sum_K s_K |K| = sum_S theta_S |S| for random node motions: the continuity source carries exactly the
  // solid's rate of volume change to the fluid (|S| the volume at the window's end, as theta's).
  Exchange e;
  double fluid_side = 0.0, solid_side = 0.0;
  for (size_t k = 0; k < e.dilatation.size(); ++k) fluid_side += e.dilatation[k] * e.fluid_volume[k];
  for (size_t t = 0; t < e.solid_theta.size(); ++t) {
    double c[4][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) c[a][d] = e.solid.x[3 * static_cast<size_t>(e.solid.tets[4 * t + a]) + d];
    solid_side += e.solid_theta[t] * tet_volume(c);  // the overlaps are of the unmoved solid
  }
  double scale = 0.0;
  for (size_t t = 0; t < e.solid_theta.size(); ++t) scale += std::abs(e.solid_theta[t]);
  EXPECT_GT(std::abs(solid_side), 0.0);
  EXPECT_NEAR(fluid_side, solid_side, 1e-12 * scale);
}

TEST(FluidSolidExchange, PenaltyOnTheSolidIsMinusTheFluidsAbsorption) {
  // Newton's third law, exactly: sum over pairs of the solid's penalty force = sum over fluid tets of the
  // lumped absorption sigma_K |K| (ubar_K - u_s,K) the fluid felt, for any fluid velocity.
  Exchange e;
  const size_t nf = e.fluid.num_tets(), np = e.ws.pairs.size();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<double> fluid_node_u(e.fluid.x.size()), ubar(3 * nf), ubar_old(3 * nf, 0.0);
  for (double& v : fluid_node_u) v = u(rng);
  tet_mean_vectors(fluid_node_u, e.fluid.tets, ubar, 0, nf);
  std::vector<double> penalty(3 * np), force(3 * np);
  FluidToSolidArgs a;
  a.rho = e.rho, a.beta = e.beta, a.dt = e.dt;
  a.pairs = e.ws.pairs, a.pair_volume = e.volume, a.fluid_velocity = ubar, a.fluid_velocity_old = ubar_old;
  a.target = e.target, a.pair_weight = e.weight, a.penalty = penalty, a.force = force;
  fluid_to_solid_pairs(a, 0, np);
  double solid_side[3] = {0, 0, 0}, fluid_side[3] = {0, 0, 0}, scale = 0.0;
  for (size_t p = 0; p < np; ++p)
    for (int d = 0; d < 3; ++d) {
      solid_side[d] += penalty[3 * p + d];
      scale += std::abs(penalty[3 * p + d]);
    }
  for (size_t k = 0; k < nf; ++k)
    for (int d = 0; d < 3; ++d)
      fluid_side[d] += e.sigma[k] * e.fluid_volume[k] * (ubar[3 * k + d] - e.target[3 * k + d]);
  ASSERT_GT(scale, 1e3);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(solid_side[d], fluid_side[d], 1e-13 * scale) << d;
}

TEST(FluidSolidExchange, AFluidAtRestGivesArchimedesForce) {
  // u = 0 everywhere and u_s = 0: the force is -f V_s, V_s the solid volume (all of it inside the fluid).
  Exchange e({0, 0, 0}, false);
  const size_t nf = e.fluid.num_tets(), np = e.ws.pairs.size();
  std::vector<double> zero(3 * nf, 0.0), penalty(3 * np), force(3 * np);
  FluidToSolidArgs a;
  a.rho = e.rho, a.beta = e.beta, a.dt = e.dt;
  a.body_force[2] = -e.rho * 9.81;
  a.pairs = e.ws.pairs, a.pair_volume = e.volume, a.fluid_velocity = zero, a.fluid_velocity_old = zero;
  a.target = e.target, a.pair_weight = e.weight, a.penalty = penalty, a.force = force;
  fluid_to_solid_pairs(a, 0, np);
  std::vector<double> node_force(e.solid.x.size(), 1.0);  // overwritten
  gather_to_solid_nodes(e.ws.pairs, force, 3, e.solid.tets, node_force);
  double total[3] = {0, 0, 0};
  for (size_t n = 0; n < node_force.size() / 3; ++n)
    for (int d = 0; d < 3; ++d) total[d] += node_force[3 * n + d];
  const double archimedes = e.rho * 9.81 * total_volume(e.solid);
  EXPECT_NEAR(total[2], archimedes, 1e-12 * archimedes);
  EXPECT_NEAR(total[0], 0.0, 1e-12 * archimedes);
  EXPECT_NEAR(total[1], 0.0, 1e-12 * archimedes);
}

TEST(FluidSolidExchange, ARigidTranslationIsTheTargetVelocityEverywhereInTheSolid) {
  const std::array<double, 3> u{0.3, -1.2, 2.5};
  Exchange e(u, false);
  size_t cells = 0;
  for (size_t k = 0; k < e.fluid.num_tets(); ++k) {
    if (e.solid_volume[k] == 0.0) continue;
    ++cells;
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(e.target[3 * k + d], u[d], 1e-14) << k;
    EXPECT_DOUBLE_EQ(e.sigma[k], e.beta * e.rho * e.fraction[k] / e.dt);
  }
  EXPECT_GT(cells, 20u);
}

// --- runs of the immersed block ---

RunOptions quiet() {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  return o;
}

Scene block_scene(std::vector<std::string> overrides = {}) {
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/immersed_block.yaml", overrides);
}

TEST(FluidSolidRun, ANeutrallyBuoyantBlockStaysAtRest) {
  Simulation sim(block_scene(), quiet());
  while (sim.step() < sim.total_steps()) sim.step_once();
  const Store& store = sim.world().store;
  const auto force = store.table(coupling::state_table).span<double>("force");
  const double archimedes = 1000.0 * 9.81 * 0.008;  // rho_f g V = 78.48 N, the block's weight
  EXPECT_NEAR(force[2], archimedes, 1e-6 * archimedes);
  EXPECT_NEAR(force[0], 0.0, 1e-6 * archimedes);
  EXPECT_NEAR(force[1], 0.0, 1e-6 * archimedes);
  double speed = 0.0;
  for (double v : store.table(solid::node_table).span<double>("v")) speed = std::max(speed, std::abs(v));
  // Weight and buoyancy cancel to round-off: g dt_total = 0.2 m/s would be the speed without the fluid.
  EXPECT_LT(speed, 1e-9);
  EXPECT_GT(store.table(coupling::state_table).span<int64_t>("exchanges")[0], 3);
}

// The store is the fluid's only copy of what the coupling hands it: the solver reads the absorption (and
// with it the target velocity) where the exchange wrote them, at t = 0 and after every window.
TEST(FluidSolidRun, TheFluidReadsTheCouplingsColumnsInPlace) {
  Simulation sim(
      block_scene({"solid.initial_velocity=[{velocity: [0.05, 0, 0.1]}]", "fluid_solid.dilatation=true"}),
      quiet());
  const FluidModel* fluid = nullptr;
  for (const auto& m : sim.world().models)
    if (auto* f = dynamic_cast<const FluidModel*>(m.get())) fluid = f;
  ASSERT_NE(fluid, nullptr);
  const Table& tets = sim.world().store.table(fluid::tet_table);
  for (int window = 0; window < 3; ++window) {
    EXPECT_EQ(fluid->solver().absorption().data(), tets.span<const double>("absorption").data());
    for (int64_t k = 0; k < fluid->substeps(); ++k) sim.step_once();
  }
  double largest = 0.0;
  for (double s : fluid->solver().absorption()) largest = std::max(largest, s);
  EXPECT_GT(largest, 0.0);  // the block is seen
}

// fluid_solid.relaxation_time tau: every cell's absorption is rho_f alpha / tau at any fluid.dt (beta =
// fluid.dt / tau), where beta alone gives beta rho_f alpha / fluid.dt, which doubles as fluid.dt halves.
TEST(FluidSolidRun, ARelaxationTimeGivesTheSameAbsorptionAtEveryFluidStep) {
  const double tau = 0.02, rho = 1000.0;
  for (const char* dt : {"0.005", "0.0025"}) {
    Simulation sim(block_scene({"fluid_solid.beta=null", "fluid_solid.relaxation_time=0.02",
                                std::string("fluid.dt=") + dt, "time.end=0.01"}),
                   quiet());
    while (sim.step() < sim.total_steps()) sim.step_once();
    const Table& cells = sim.world().store.table(fluid::tet_table);
    const auto alpha = cells.span<const double>("solid_fraction");
    const auto sigma = cells.span<const double>("absorption");
    size_t cut = 0;
    for (size_t k = 0; k < alpha.size(); ++k) {
      EXPECT_NEAR(sigma[k], rho * alpha[k] / tau, 1e-12 * rho / tau) << "cell " << k << " at fluid.dt " << dt;
      cut += alpha[k] > 0.0 ? 1 : 0;
    }
    EXPECT_GT(cut, 0u);
  }
}

// A moving block (initial velocity) so the penalty and inertia terms are exercised.
std::vector<std::string> moving() {
  return {"solid.initial_velocity=[{velocity: [0.05, 0, 0.1]}]", "solid.materials[0].density=1500"};
}

TEST(FluidSolidRun, OneAndTwoThreadsGiveTheSameBits) {
  test::TempDir dir;
  const Scene scene = block_scene(moving());
  const RunResult one = test::run_scene(scene, dir.path() / "t1", 1);
  const RunResult two = test::run_scene(scene, dir.path() / "t2", 2);
  ASSERT_TRUE(one.completed);
  EXPECT_EQ(one.state_hash, two.state_hash);
}

TEST(FluidSolidRun, ARestartFromMidWindowContinuesBitForBit) {
  test::TempDir dir;
  const Scene scene = block_scene(moving());
  const RunResult whole = test::run_scene(scene, dir.path() / "whole", 1);
  // Stop inside a window of sub-steps (not on a fluid step), then continue from the checkpoint.
  const auto [first, rest] = test::stop_and_resume(scene, dir.path() / "split", 1, whole.steps / 2 + 3);
  EXPECT_FALSE(first.completed);
  ASSERT_TRUE(rest.completed);
  EXPECT_EQ(rest.state_hash, whole.state_hash);
}

// Water (mu = 1e-3 Pa s) around the neutrally buoyant block, at rest and thrown. With the quasi-static
// pressure subscale tau = h^2 / (4 mu) is ~1e6 x dt / rho; FGMRES restarted every 50 iterations stalls at
// its cap on the thrown block, and the run must stop saying so (it once completed with every Schur solve at
// its cap). Restarted every 100 (the default) both subscales converge: at rest the state is the
// hydrostatic one, Archimedes' force to 1e-6 (the Schur tolerance 1e-8 on a pressure of 4.9 kPa leaves
// ~1e-9 of it) and the block at rest; thrown, the run completes.
TEST(FluidSolidRun, WaterAroundABlockConvergesWithEitherSubscaleAndAStalledSolveStops) {
  std::vector<std::string> thrown = moving();
  thrown.insert(thrown.end(), {"fluid.viscosity=1.0e-3", "fluid.schur_restart=50"});
  try {
    Simulation sim(block_scene(thrown), quiet());
    sim.run();
    FAIL() << "expected the fluid guard to stop the run";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("linear solve did not converge"), std::string::npos) << what;
    EXPECT_NE(what.find("fluid.schur_restart"), std::string::npos) << what;
  }
  test::TempDir dir;
  for (const char* subscale : {"quasi_static", "dynamic"}) {
    SCOPED_TRACE(subscale);
    const std::string choice = std::string("fluid.pressure_subscale=") + subscale;
    Simulation sim(block_scene({"fluid.viscosity=1.0e-3", choice}), quiet());
    while (sim.step() < sim.total_steps()) sim.step_once();
    const Store& store = sim.world().store;
    const auto force = store.table(coupling::state_table).span<double>("force");
    const double archimedes = 1000.0 * 9.81 * 0.008;
    EXPECT_NEAR(force[2], archimedes, 1e-6 * archimedes);
    double speed = 0.0;
    for (double v : store.table(solid::node_table).span<double>("v")) speed = std::max(speed, std::abs(v));
    EXPECT_LT(speed, 1e-9);
    std::vector<std::string> water = moving();
    water.insert(water.end(), {"fluid.viscosity=1.0e-3", choice});
    EXPECT_TRUE(test::run_scene(block_scene(water), dir.path() / subscale, 1).completed);
  }
  // The dynamic subscale is state: a restart inside a window continues bit for bit.
  std::vector<std::string> dynamic = moving();
  dynamic.insert(dynamic.end(), {"fluid.viscosity=1.0e-3", "fluid.pressure_subscale=dynamic"});
  const Scene moving_water = block_scene(dynamic);
  const RunResult whole = test::run_scene(moving_water, dir.path() / "whole", 1);
  ASSERT_TRUE(whole.completed);
  const auto [first, rest] =
      test::stop_and_resume(moving_water, dir.path() / "split", 1, whole.steps / 2 + 3);
  ASSERT_TRUE(rest.completed);
  EXPECT_EQ(rest.state_hash, whole.state_hash);
}

TEST(FluidSolidRun, TooFewSubstepsAreRefusedWithTheNumberNeeded) {
  try {
    Simulation sim(block_scene({"fluid_solid.substeps=1"}), quiet());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fluid_solid.substeps = 1"), std::string::npos) << what;
    EXPECT_NE(what.find("above the solid's stable step"), std::string::npos) << what;
  }
}

TEST(FluidSolidRun, AnEndTimeOffTheFluidStepIsRefused) {
  EXPECT_THROW(Simulation(block_scene({"time.end=0.0123"}), quiet()), Error);
}

}  // namespace
}  // namespace rift

namespace rift {
namespace {

void check_wetted_faces(bool dilatation) {
  // fluid_solid.force: wetted_faces with the block's top and bottom wetted (type fluid_pressure), in the
  // box of fluid at rest, without gravity, the pressure on the box's top ramping at 5e6 Pa/s: the fluid's
  // pressure is uniform, p_top(t), and every wetted face must carry p_top at the last fluid step (1e5 Pa at
  // t = 0.02 s), the two faces' pushes cancelling. Tolerance 2e-5 relative: the block's compression under
  // the rising pressure draws fluid in, and that flow's dynamic pressure is what separates p from p_top
  // (measured 6.7e-5 at E = 1e9, 8.8e-6 at E = 1e10: it falls with 1/E).
  std::vector<std::string> wet{
      "fluid_solid.force=wetted_faces",
      "solid.materials[0].young=1.0e10",
      "solid.gravity=[0, 0, 0]",
      "fluid.body_force=[0, 0, 0]",
      "fluid.boundaries[5]={surface: zmax, type: pressure, value: {ramp: {value: 0, "
      "start_time: 0, rate: 5.0e6}}}",
      "solid.boundaries=[{surface: zmin, type: fluid_pressure}, {surface: zmax, type: "
      "fluid_pressure}]",
      std::string("fluid_solid.dilatation=") + (dilatation ? "true" : "false")};
  Simulation sim(block_scene(wet), quiet());
  while (sim.step() < sim.total_steps()) sim.step_once();
  const Store& store = sim.world().store;
  const Table& faces = store.table(solid::face_table);
  const auto p = faces.span<double>("fluid_pressure");
  const auto corner = faces.span<double>("corner_force");
  ASSERT_EQ(faces.size(), 16u);  // 2 faces x 2 x 2 cells x 2 triangles
  const double p_top = 5.0e6 * sim.time();
  double push = 0.0;
  for (size_t f = 0; f < faces.size(); ++f) {
    EXPECT_NEAR(p[f], p_top, 2e-5 * p_top) << f;
    for (int k = 0; k < 3; ++k) push += std::abs(corner[9 * f + 3 * k + 2]);
  }
  // Each face pushes p A on the block (the corner forces were computed from the previous window's
  // pressure, one fluid step lower): 2 x 0.04 m^2.
  EXPECT_NEAR(push, 2 * 0.04 * 5.0e6 * (sim.time() - 0.005), 1e-3 * push);
  const auto force = store.table(coupling::state_table).span<double>("force");
  EXPECT_NEAR(force[2], 0.0, 1e-6 * p_top * 0.04);
}

TEST(FluidSolidRun, WettedFacesCarryTheFluidsPressure) {
  check_wetted_faces(false);
}

// With the continuity source the fluid lets the block shrink instead of resisting it; the faces still
// carry p_top (measured residue 9.2e-6 with and 8.8e-6 without: the compression-driven flow is tiny here).
TEST(FluidSolidRun, WettedFacesCarryTheFluidsPressureWithTheSolidsDilatation) {
  check_wetted_faces(true);
}

}  // namespace
}  // namespace rift
