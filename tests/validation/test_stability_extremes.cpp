// Stability at the extremes (issue 7, solid side): each case either runs stably with bounded energy or
// stops with a diagnosis that names the cause and what to change; never a NaN in the state or an output
// file, never a hang. docs/stability.md lists the cases, what happens and why.
//
// "Bounded energy": the balance W_ext = KE + E_el + E_joint + D_damp + D_frac (docs/architecture.md)
// holds to 5 % of the largest energy scale seen so far, sampled every 16 steps. A stable central-difference
// run keeps that error at the level of its time discretisation and it does not grow: 1e-4 of the work on
// the Brazilian disc, 0.3-0.9 % on the wave bar, whose velocity step is a discontinuity the scheme cannot
// resolve (flat over 2,500 steps at 1.5 x and 1.75 x the estimate). An unstable run grows it by a
// constant factor per step (1.6 at 2 x on the wave bar) and passes 5 % within a few steps of starting to.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/io/hdf5_file.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/mesh_quality.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

struct Outcome {
  bool completed = false;
  std::string diagnosis;  // the guard's message when the run stopped
  int64_t steps = 0;
  double worst_balance = 0.0;  // max |balance error| / energy scale over the samples
  bool finite = true;          // every node position and velocity finite at the end
  size_t broken = 0;
};

Outcome run_case(const Scene& scene, int threads = 2) {
  Outcome out;
  RunOptions o;
  o.threads = threads;
  o.progress = false;
  o.write_output = false;
  Simulation sim(scene, o);
  SolidModel& solid = solid_of(sim);
  double largest = 0.0;  // the largest energy scale seen so far
  auto sample = [&] {
    const SolidEnergies e = solid.energies();
    const double scale = std::abs(e.external_work) + e.kinetic + std::abs(e.elastic) +
                         std::abs(e.joint_stored) + e.damping + std::abs(e.fracture);
    largest = std::max(largest, scale);
    if (largest > 0) out.worst_balance = std::max(out.worst_balance, std::abs(e.balance_error()) / largest);
  };
  try {
    while (sim.step() < sim.total_steps()) {
      sim.step_once();
      if (sim.step() % 16 == 0) sample();
    }
    out.completed = true;
  } catch (const Error& e) {
    out.diagnosis = e.what();
  }
  out.steps = sim.step();
  for (const char* col : {"x", "v"})
    for (double c : sim.world().store.table("solid_node").span<const double>(col))
      out.finite &= std::isfinite(c);
  out.broken = solid.broken_joint_count();
  return out;
}

double stable_dt(const Scene& scene) {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  return Simulation(scene, o).world().stable_dt();
}

nlohmann::json solid_summary(const Scene& scene) {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  Simulation sim(scene, o);
  nlohmann::json j;
  solid_of(sim).summarize(j);
  return j["solid"];
}

std::string dt_override(double dt) {
  return "time.dt=" + fmt::format("{:.17g}", dt);
}

void expect_stable(const Outcome& r, const char* what) {
  EXPECT_TRUE(r.completed) << what << ": " << r.diagnosis;
  EXPECT_TRUE(r.finite) << what;
  EXPECT_LT(r.worst_balance, 0.05) << what;
  std::printf("%s: %lld steps, worst balance error %.2e of the energy scale, %zu joints broken\n", what,
              static_cast<long long>(r.steps), r.worst_balance, r.broken);
}

// --- the time step -------------------------------------------------------------------------------------

TEST(StabilityExtremes, StepAtPointNineAndOnePointFiveTimesTheStableEstimate) {
  // Continuous bar (tets only) and the jointed patch block (joints at p = 100 E set the step).
  for (const char* name : {"wave_bar.yaml", "patch_uniaxial.yaml"}) {
    const double stable = stable_dt(validation_scene(name));
    for (double factor : {0.9, 1.5}) {
      const Scene scene = validation_scene(name, {dt_override(factor * stable), "time.allow_unstable_dt=true",
                                                  "time.end=" + fmt::format("{:.17g}", 600 * stable)});
      expect_stable(run_case(scene), fmt::format("{} at {} x the stable step", name, factor).c_str());
    }
  }
}

// Twice the estimate is past the real limit on the wave bar's dev-build mesh: that run blows up after
// some 150 of its 171 steps, near its end, so a guard that checked only every N steps and not after the
// last would let it finish with a kinetic energy 250 x the work done. (The Release build meshes the bar
// slightly differently and survives 2 x.) The guard checks every 16 steps and after the last one. This
// test pins the second part without depending on when a mesh goes unstable: energy that no work fed
// (every node given 1 m/s) is reported at a step that is not a multiple of 16 only when it is the last.
TEST(StabilityExtremes, EnergyGuardChecksAfterTheLastStep) {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  Simulation sim(validation_scene("wave_bar.yaml"), o);
  for (int i = 0; i < 5; ++i) sim.step_once();
  for (double& v : sim.world().store.table("solid_node").span<double>("v")) v = 1.0;
  SolidModel& solid = solid_of(sim);
  EXPECT_FALSE(solid.check_health(StepContext{5, sim.time(), sim.dt(), false}).has_value());
  const auto diagnosis = solid.check_health(StepContext{5, sim.time(), sim.dt(), true});
  ASSERT_TRUE(diagnosis.has_value());
  EXPECT_NE(diagnosis->find("energy is not conserved at step 5"), std::string::npos) << *diagnosis;
  EXPECT_NE(diagnosis->find("What to change"), std::string::npos) << *diagnosis;
}

// Joints that hand out energy (their books: work done on them less what they store, far below zero) stop
// the run with their own diagnosis, naming the joints, where the last one broke and what to change. The
// books are set here; the run that needed the guard (the wedge scene's notch-tip zone breaking up at 0.2 ms,
// docs/speed-accuracy.md) takes 5 minutes to get there.
TEST(StabilityExtremes, JointsPuttingEnergyInStopTheRun) {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  Simulation sim(validation_scene("patch_uniaxial.yaml"), o);
  for (int i = 0; i < 16; ++i) sim.step_once();
  SolidModel& solid = solid_of(sim);
  EXPECT_FALSE(solid.check_health(StepContext{16, sim.time(), sim.dt(), false}).has_value());
  // 1 J handed out by the joints and taken up elsewhere (here by the damping), so that the balance closes:
  // what the flutter-like run did, where the general energy guard saw nothing.
  Table& book = sim.world().store.table(solid::energy_table);
  book.span<double>("joint_work")[0] += 1.0;
  book.span<double>("damping")[0] += 1.0;
  const auto diagnosis = solid.check_health(StepContext{32, sim.time(), sim.dt(), false});
  ASSERT_TRUE(diagnosis.has_value());
  EXPECT_NE(diagnosis->find("the joints are putting energy into the solid at step 32"), std::string::npos)
      << *diagnosis;
  EXPECT_NE(diagnosis->find("What to change"), std::string::npos) << *diagnosis;
}

TEST(StabilityExtremes, StepAboveTheEstimateIsRefusedUnlessAskedFor) {
  const double stable = stable_dt(validation_scene("wave_bar.yaml"));
  try {
    RunOptions o;
    o.progress = false;
    o.write_output = false;
    Simulation sim(validation_scene("wave_bar.yaml", {dt_override(1.5 * stable)}), o);
    FAIL() << "a step above the stable one was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("allow_unstable_dt"), std::string::npos) << e.what();
  }
}

// --- materials -----------------------------------------------------------------------------------------

// nu = 0.499: lambda = 250 mu. The step follows c_p = sqrt((lambda + 2 mu) / rho): for the same mesh the
// stable step must shrink by c_p(0.499) / c_p(0.25) = sqrt((0.501 / (1.499 * 0.002)) / (0.75 / (1.25 * 0.5)))
// = 11.80, to 1 % (the estimate is c_p-proportional; the 1 % allows for the damping term).
TEST(StabilityExtremes, NearlyIncompressibleSolid) {
  const Scene base = validation_scene("wave_bar.yaml");
  const Scene soft = validation_scene("wave_bar.yaml", {"solid.materials[0].poisson=0.499"});
  const double ratio = stable_dt(base) / stable_dt(soft);
  const double expected = std::sqrt((0.501 / (1.499 * 0.002)) / (0.75 / (1.25 * 0.5)));
  EXPECT_NEAR(ratio, expected, 0.01 * expected);
  std::printf("poisson 0.499: stable step %.4g s, %.4f x smaller (expected %.4f)\n", stable_dt(soft), ratio,
              expected);
  expect_stable(run_case(soft), "poisson 0.499");
}

// Joint penalty 1000 E: the joint limit dt_joint = h sqrt(rho / p) (femdem.md 1d) falls by sqrt(10) from
// p = 100 E, exactly (same mesh), and the run stays stable with the smaller step.
TEST(StabilityExtremes, JointPenaltyThousandTimesYoung) {
  const Scene base = validation_scene("patch_uniaxial.yaml");
  const Scene stiff = validation_scene("patch_uniaxial.yaml", {"solid.materials[0].fracture.penalty=4.0e13"});
  const double ratio = solid_summary(base)["joint_stable_dt"].get<double>() /
                       solid_summary(stiff)["joint_stable_dt"].get<double>();
  EXPECT_NEAR(ratio, std::sqrt(10.0), 1e-9 * std::sqrt(10.0));
  expect_stable(run_case(validation_scene("patch_uniaxial.yaml",
                                          {"solid.materials[0].fracture.penalty=4.0e13", "time.end=1.0e-4"})),
                "joint penalty 1000 E");
}

// --- geometry ------------------------------------------------------------------------------------------

// A 2 x 2 x 2 Kuhn block of 1 cm cubes whose centre node is pushed towards x = 2 cm until one tet has a
// `angle` degree dihedral angle (bisection on the push), written to dir/sliver.msh; or the block unperturbed.
void write_sliver_block(const test::TempDir& dir, bool perturbed, double angle = 2.0) {
  TetMesh mesh = generate_lattice_box({2, 2, 2}, {0.02, 0.02, 0.02});
  const size_t centre = 1 + 3 * (1 + 3 * 1);
  const auto start = mesh.nodes[centre];
  double lo = 0.0, hi = 0.01;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    mesh.nodes[centre] = {start[0] + mid, start[1], start[2]};
    (measure_quality(mesh).min_dihedral_deg > angle ? lo : hi) = mid;
  }
  mesh.nodes[centre] = {start[0] + (perturbed ? lo : 0.0), start[1], start[2]};
  const MeshQuality q = measure_quality(mesh);
  if (perturbed) {
    ASSERT_NEAR(q.min_dihedral_deg, angle, 1e-6 * angle);
  }
  ASSERT_EQ(q.inverted, 0u);
  write_msh(mesh, (dir / "sliver.msh").string());
}

// The block pushed at its xmax face at 0.1 m/s; solid_extra: more lines of the solid section.
Scene sliver_scene(const test::TempDir& dir, const std::string& solid_extra = "") {
  const auto parsed = read_scene_text(
      "scene: {name: sliver}\ntime: {end: 2.0e-5}\nmesh: {file: sliver.msh}\n"
      "solid:\n  materials: [{name: limestone, density: 2650, young: 4.0e10, poisson: 0.25, damping: 0.05}]\n"
      "  boundaries:\n    - {surface: xmin, type: fixed}\n"
      "    - {surface: xmax, type: velocity, components: [x], direction: [-0.1, 0, 0]}\n" +
          solid_extra,
      (dir / "sliver.yaml").string(), dir.path().string());
  if (!parsed.scene) throw Error(parsed.errors.front().format());
  return *parsed.scene;
}

// The stable step is then set by the sliver, and the block runs stably.
TEST(StabilityExtremes, SliverTetWithATwoDegreeDihedralAngle) {
  test::TempDir dir;
  write_sliver_block(dir, false);
  const double without = stable_dt(sliver_scene(dir));
  write_sliver_block(dir, true);
  const double with_sliver = stable_dt(sliver_scene(dir));
  // The unperturbed block's step is the sliver's times the ratio of smallest heights, > 10.
  EXPECT_GT(without / with_sliver, 10.0);
  std::printf("sliver: stable step %.4g s, %.1f x below the unperturbed block's\n", with_sliver,
              without / with_sliver);
  expect_stable(run_case(sliver_scene(dir)), "sliver tet, 2 degree dihedral");
}

// Flatter slivers: at 0.5 degrees the sliver's step is ~1e-3 of the median tet's, which the set-up names in
// the log and runs; at 0.02 degrees (~4e-6) it refuses the mesh, naming the tet, where it is, its shape
// and what to change, before any step.
TEST(StabilityExtremes, AFlatSliverIsNamedAndBeyondTenThousandTimesRefused) {
  test::TempDir dir;
  write_sliver_block(dir, true, 0.5);
  EXPECT_NO_THROW(stable_dt(sliver_scene(dir)));
  write_sliver_block(dir, true, 0.02);
  try {
    stable_dt(sliver_scene(dir));
    ADD_FAILURE() << "a 0.02 degree sliver was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    for (const char* part :
         {"mesh: tet ", " at (", "x the mesh's median", "dihedral angles", "radius ratio", "What to change"})
      EXPECT_NE(m.find(part), std::string::npos) << m << "\n  should mention " << part;
  }
}

// Mass scaling to the unperturbed block's step (solid.mass_scaling_step): the sliver's corners get heavier,
// the step is the target exactly, and the run is stable with the energy balance bounded. The block shares
// its nodes, so the per-node bound is a mass-weighted mean of its tets' estimates, not a bound on the
// assembly: at 1.5 x the scaled step the run goes unstable and the energy guard stops it, naming the step.
// (Mass scaling is meant for fracture zones, where every node has one tet: the jointed case below.)
TEST(StabilityExtremes, MassScalingLiftsTheSliversStep) {
  test::TempDir dir;
  write_sliver_block(dir, false);
  const double target = 0.9 * stable_dt(sliver_scene(dir));
  write_sliver_block(dir, true);
  const std::string scaling = fmt::format("  mass_scaling_step: {:.17g}\n", target);
  const Scene scaled = sliver_scene(dir, scaling);
  const nlohmann::json s = solid_summary(scaled);
  EXPECT_DOUBLE_EQ(s["stable_dt"].get<double>(), target);
  const auto& m = s["mass_scaling"];
  EXPECT_GT(m["scaled_nodes"].get<size_t>(), 0u);
  EXPECT_LT(m["scaled_nodes"].get<size_t>(), s["nodes"].get<size_t>());
  std::printf(
      "sliver, mass scaling to %.4g s: %zu of %zu nodes heavier, +%.3g %% of the mass, up to %.1f x\n",
      target, m["scaled_nodes"].get<size_t>(), s["nodes"].get<size_t>(),
      100 * m["added_fraction"].get<double>(), m["largest_factor"].get<double>());
  expect_stable(run_case(scaled), "sliver with mass scaling");
  Scene fast = sliver_scene(dir, scaling);
  fast.time.dt = 1.5 * target;
  fast.time.allow_unstable_dt = true;
  const Outcome r = run_case(fast);
  EXPECT_TRUE(r.finite);
  if (!r.completed) {
    EXPECT_NE(r.diagnosis.find("a step above the stable one"), std::string::npos) << r.diagnosis;
  }
  std::printf("sliver with mass scaling at 1.5 x: %s\n", r.completed ? "stable" : r.diagnosis.c_str());
}

// The jointed patch block (private nodes, joints at p = 100 E set the step) with mass scaling to twice its
// step. The scaled step is the per-node bound, sharper than the unscaled one (which assumes three of the
// stiffest joints at the lightest node): the run is stable at 0.9 and 1.1 x it, and measured unstable from
// 1.2 x on; at 1.5 x the energy guard stops it and names the step.
TEST(StabilityExtremes, MassScalingInAFractureZoneAtPointNineAndOnePointFiveTimesTheScaledStep) {
  const double stable = stable_dt(validation_scene("patch_uniaxial.yaml"));
  const std::string scaling = fmt::format("solid.mass_scaling_step={:.17g}", 2.0 * stable);
  const nlohmann::json s = solid_summary(validation_scene("patch_uniaxial.yaml", {scaling}));
  EXPECT_DOUBLE_EQ(s["stable_dt"].get<double>(), 2.0 * stable);
  std::printf("jointed patch, mass scaling to 2 x its step: %zu of %zu nodes heavier, +%.3g %% of the mass\n",
              s["mass_scaling"]["scaled_nodes"].get<size_t>(), s["nodes"].get<size_t>(),
              100 * s["mass_scaling"]["added_fraction"].get<double>());
  auto at = [&](double factor) {
    return run_case(validation_scene(
        "patch_uniaxial.yaml", {scaling, dt_override(factor * 2.0 * stable), "time.allow_unstable_dt=true",
                                "time.end=" + fmt::format("{:.17g}", 1200 * stable)}));
  };
  for (double factor : {0.9, 1.1})
    expect_stable(at(factor),
                  fmt::format("jointed patch, mass scaled, {} x the scaled step", factor).c_str());
  const Outcome fast = at(1.5);
  EXPECT_TRUE(fast.finite);
  EXPECT_FALSE(fast.completed);
  EXPECT_NE(fast.diagnosis.find("a step above the stable one"), std::string::npos) << fast.diagnosis;
}

// --- loads ---------------------------------------------------------------------------------------------

// The notch pressurised 100 x faster than the paper's ramp (2e6 MPa/s): a dynamic fracturing run.
TEST(StabilityExtremes, PressureRampHundredTimesThePapers) {
  const Outcome r = run_case(validation_scene("notch_pressure_ramp.yaml"));
  expect_stable(r, "notch pressure ramp at 2e12 Pa/s");
  EXPECT_GT(r.broken, 0u);  // it does fracture
}

// A compressive traction of 1e12 Pa = 25 E on the quickstart bar inverts the loaded tets: the run stops
// at the step it happens, names the inverted tets, the cause and the remedy, and what it wrote before
// holds no NaN.
TEST(StabilityExtremes, LoadThatInvertsAnElementStopsWithADiagnosis) {
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  const Scene scene =
      load_scene(path, {"solid.boundaries[1].value=1", "solid.boundaries[1].direction=[-1.0e12, 0, 0]",
                        "output.interval=1.0e-7"});
  test::TempDir dir;
  RunOptions o;
  o.out_dir = dir.path();
  o.progress = false;
  std::string what;
  try {
    Simulation(scene, o).run();
  } catch (const Error& e) {
    what = e.what();
  }
  ASSERT_FALSE(what.empty()) << "the run did not stop";
  std::printf("inverting load: %s\n", what.c_str());
  EXPECT_NE(what.find("inverted"), std::string::npos) << what;
  EXPECT_NE(what.find("What to change"), std::string::npos) << what;
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("rift_0", 0) != 0) continue;
    const H5File f(entry.path(), H5File::Mode::read);
    for (const char* field : {"/solid/points", "/solid/velocity", "/solid/stress"})
      for (double v : f.read<double>(field)) ASSERT_TRUE(std::isfinite(v)) << name << field;
    ++files;
  }
  EXPECT_GT(files, 0u);
}

}  // namespace
}  // namespace rift::validation
