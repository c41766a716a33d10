// The fluid in scenes: the fluid section's reader, the run loop's step for a fluid scene, the store
// (fluid tables only when there is a fluid, solid tables only with a solid), restart bit for bit, the
// same state on 1 and 2 threads, and the guards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_run_support.hpp"

using namespace rift;
namespace fs = std::filesystem;

namespace {

const std::string kScenes = std::string(RIFT_SOURCE_DIR) + "/scenes/";

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("rift_test_fluid_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The cavity at 8 x 8 cells, 10 steps: small enough for a unit test, still a driven, convecting flow.
Scene small_cavity(std::vector<std::string> extra = {}) {
  std::vector<std::string> o{"time.end=1.0", "mesh.generate.cells=[8, 8, 1]",
                             "mesh.generate.box=[1, 1, 0.125]", "output.interval=0.5"};
  o.insert(o.end(), extra.begin(), extra.end());
  return load_scene(kScenes + "examples/cavity.yaml", o);
}

// The channel with the coupled Schur solve and BoomerAMG, 6 steps (the pressure ramp still rising).
Scene small_channel() {
  return load_scene(kScenes + "validation/poiseuille.yaml",
                    {"time.end=6.0", "mesh.generate.cells=[8, 4, 1]"});
}

}  // namespace

TEST(FluidScene, ReadsTheCavityScene) {
  const Scene s = load_scene(kScenes + "examples/cavity.yaml");
  ASSERT_TRUE(s.fluid);
  EXPECT_FALSE(s.solid);
  const FluidSpec& f = *s.fluid;
  EXPECT_EQ(f.density, 1.0);
  EXPECT_EQ(f.viscosity, 0.01);
  EXPECT_EQ(f.dt, 0.1);
  EXPECT_EQ(f.theta, 1.0);
  EXPECT_FALSE(f.supg);
  EXPECT_EQ(f.coupling, FluidSpec::Coupling::projection);
  EXPECT_EQ(f.picard_max_iterations, 3);
  EXPECT_EQ(f.on_picard_failure, FluidSpec::OnPicardFailure::continue_run);
  ASSERT_EQ(f.boundaries.size(), 6u);
  EXPECT_EQ(f.boundaries[0].kind, FluidBoundarySpec::Kind::velocity);
  EXPECT_EQ(f.boundaries[0].direction, (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(f.boundaries[0].function(3.0), 1.0);  // value defaults to 1
  EXPECT_EQ(f.boundaries[4].kind, FluidBoundarySpec::Kind::free_slip);
  ASSERT_EQ(s.probes.size(), 2u);
  EXPECT_EQ(s.probes[0].field, "fluid.velocity");
  EXPECT_EQ(s.probes[0].component, "x");
  EXPECT_EQ(s.probes[1].component, "y");
  EXPECT_EQ(s.probes[0].points.size(), 15u);
  ASSERT_TRUE(s.mesh.generate && s.mesh.generate->cells);
  EXPECT_EQ(*s.mesh.generate->cells, (std::array<int, 3>{16, 16, 1}));
}

TEST(FluidScene, ResolvedSceneReadsBackToTheSameScene) {
  for (const char* name : {"examples/cavity.yaml", "validation/poiseuille.yaml"}) {
    const Scene s =
        load_scene(kScenes + name, {"fluid.scheme=crank_nicolson", "fluid.body_force=[0, 0, -9.81]"});
    SceneLoadResult again = read_scene_text(s.resolved_yaml, "resolved", kScenes);
    ASSERT_TRUE(again.errors.empty()) << again.errors[0].format() << "\n" << s.resolved_yaml;
    EXPECT_EQ(again.scene->hash, s.hash) << s.resolved_yaml;
    EXPECT_EQ(again.scene->fluid->theta, 0.5);
  }
}

TEST(FluidScene, PressureRampAndTheta) {
  const Scene s = load_scene(kScenes + "validation/poiseuille.yaml", {"fluid.scheme=crank_nicolson"});
  const FluidBoundarySpec& in = s.fluid->boundaries[0];
  EXPECT_EQ(in.kind, FluidBoundarySpec::Kind::pressure);
  EXPECT_DOUBLE_EQ(in.function(1.0), 16.0);
  EXPECT_DOUBLE_EQ(in.function(5.0), 32.0);
  EXPECT_EQ(s.fluid->theta, 0.5);
}

TEST(FluidScene, FluidMeshWithoutTopLevelMesh) {
  const std::string yaml = R"(scene: {name: own_mesh}
time: {end: 0.2}
fluid:
  mesh:
    generate: {box: [1, 1, 0.25], cells: [4, 4, 1]}
  density: 1.0
  viscosity: 0.01
  dt: 0.1
  theta: 0.75
  boundaries:
    - {surface: xmin, type: velocity, direction: [1, 0, 0]}
    - {surface: xmax, type: outflow}
    - {surface: ymin, type: no_slip}
    - {surface: ymax, type: no_slip}
    - {surface: zmin, type: free_slip}
    - {surface: zmax, type: free_slip}
)";
  SceneLoadResult r = read_scene_text(yaml, "inline", kScenes);
  ASSERT_TRUE(r.errors.empty()) << r.errors[0].format();
  ASSERT_TRUE(r.scene->fluid->mesh);
  EXPECT_EQ(r.scene->fluid->theta, 0.75);
  // fluid.mesh keys are documented (and checked) as the mesh section's.
  const std::set<std::string> consumed(r.consumed_keys.begin(), r.consumed_keys.end());
  EXPECT_TRUE(consumed.count("mesh.generate.cells"));
  EXPECT_TRUE(consumed.count("fluid.mesh"));
  SceneLoadResult again = read_scene_text(r.scene->resolved_yaml, "resolved", kScenes);
  ASSERT_TRUE(again.errors.empty()) << again.errors[0].format();
  EXPECT_EQ(again.scene->hash, r.scene->hash);
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  Simulation sim(*r.scene, o);
  EXPECT_EQ(sim.total_steps(), 2);
  EXPECT_EQ(sim.world().mesh.tets.size(), 4u * 4u * 6u);
  sim.run();
}

TEST(FluidScene, TwoMeshesForOneFluidAreRefused) {
  SceneLoadResult r = read_scene_text(R"(scene: {name: two_meshes}
time: {end: 0.2}
mesh:
  generate: {box: [1, 1, 0.25], cells: [4, 4, 1]}
fluid:
  mesh:
    generate: {box: [1, 1, 0.25], cells: [8, 8, 1]}
  density: 1.0
  viscosity: 0.01
  dt: 0.1
  boundaries:
    - {surface: ymin, type: no_slip}
)",
                                      "inline", kScenes);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].key_path, "mesh");
  EXPECT_EQ(r.errors[0].line, 3);  // the mesh: key
  EXPECT_NE(r.errors[0].expected.find("no top-level mesh when fluid.mesh is given"), std::string::npos)
      << r.errors[0].format();
}

TEST(FluidScene, UnknownSurfaceListsTheMeshSurfaces) {
  try {
    RunOptions o;
    o.write_output = false;
    Simulation sim(small_cavity({"fluid.boundaries[0].surface=lid"}), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("fluid.boundaries[0].surface: the mesh has no surface 'lid'"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("xmin, xmax, ymin, ymax, zmin, zmax"), std::string::npos) << msg;
  }
}

TEST(FluidScene, StepIsTheFluidStep) {
  RunOptions o;
  o.write_output = false;
  {
    Simulation sim(small_cavity({"time.dt=0.1"}), o);  // equal: fine
    EXPECT_EQ(sim.dt(), 0.1);
    EXPECT_EQ(sim.total_steps(), 10);
  }
  try {
    Simulation sim(small_cavity({"time.dt=0.05"}), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("disagrees with the fluid step"), std::string::npos) << e.what();
  }
  try {
    Simulation sim(small_cavity({"time.end=1.05"}), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a whole number of fluid steps"), std::string::npos) << e.what();
  }
}

TEST(FluidScene, ModelsAndTablesFollowTheScene) {
  RunOptions o;
  o.write_output = false;
  Scene cavity = small_cavity();
  ASSERT_FALSE(cavity.probes.empty());
  Simulation probed(cavity, o);
  cavity.probes.clear();
  Simulation fluid(cavity, o);
  ASSERT_EQ(fluid.world().models.size(), 1u);
  EXPECT_EQ(fluid.world().models[0]->name(), "fluid");
  for (const auto& t : fluid.world().store.tables()) EXPECT_EQ(t->name().rfind("fluid_", 0), 0u) << t->name();
  EXPECT_TRUE(fluid.world().store.has("fluid_node"));
  // The probes are one more model, with no tables of their own.
  ASSERT_EQ(probed.world().models.size(), 2u);
  EXPECT_EQ(probed.world().models[1]->name(), "probes");
  EXPECT_EQ(probed.world().store.tables().size(), fluid.world().store.tables().size());
  Simulation dry(load_scene(kScenes + "examples/quickstart.yaml"), o);
  for (const auto& m : dry.world().models) EXPECT_NE(m->name(), "fluid");
  for (const auto& t : dry.world().store.tables()) EXPECT_NE(t->name().rfind("fluid", 0), 0u) << t->name();
}

TEST(FluidScene, OutputsFieldsSeriesAndSummary) {
  const fs::path dir = fresh_dir("outputs");
  const RunResult r = test::run_scene(small_cavity(), dir, 1);
  EXPECT_TRUE(r.completed);
  EXPECT_EQ(r.steps, 10);
  const std::string csv = read_text(dir / "timeseries.csv");
  for (const char* c : {"fluid_picard_iterations", "fluid_velocity_iterations", "fluid_schur_iterations",
                        "fluid_pressure_iterations", "fluid_divergence_l2", "fluid_divergence_max",
                        "fluid_cfl", "fluid_kinetic_energy"})
    EXPECT_NE(csv.find(c), std::string::npos) << c;
  const std::string xdmf = read_text(dir / "rift.xdmf");
  for (const char* f :
       {"Name=\"fluid\"", "Name=\"velocity\"", "Name=\"pressure\"", "Name=\"divergence\"", "Name=\"cfl\""})
    EXPECT_NE(xdmf.find(f), std::string::npos) << f;
  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"));
  const auto& f = summary["metrics"]["fluid"];
  EXPECT_GT(f["kinetic_energy"].get<double>(), 0.0);
  EXPECT_GT(f["max_cfl"].get<double>(), 0.1);
  EXPECT_EQ(f["picard_failures"].get<int64_t>(), 10);  // 3 iterations per step, never converged
  fs::remove_all(dir);
}

TEST(FluidScene, RestartIsBitwiseIdentical) {
  for (const Scene& scene : {small_cavity(), small_channel()}) {
    SCOPED_TRACE(scene.name);
    const fs::path a = fresh_dir("straight"), b = fresh_dir("restarted");
    const RunResult straight = test::run_scene(scene, a, 1);
    ASSERT_TRUE(straight.completed);
    const int64_t half = straight.steps / 2;
    const RunResult first = test::run_scene(scene, b, 1, half);
    EXPECT_EQ(first.steps, half);
    const RunResult second = test::run_scene(scene, b, 1, std::nullopt, true);
    EXPECT_TRUE(second.completed);
    EXPECT_EQ(hex64(second.state_hash), hex64(straight.state_hash));
    EXPECT_EQ(read_text(a / "timeseries.csv"), read_text(b / "timeseries.csv"));
    auto sa = nlohmann::json::parse(read_text(a / "summary.json"))["metrics"];
    auto sb = nlohmann::json::parse(read_text(b / "summary.json"))["metrics"];
    EXPECT_EQ(sa.dump(), sb.dump());
    fs::remove_all(a);
    fs::remove_all(b);
  }
}

TEST(FluidScene, SameStateOnOneAndTwoThreads) {
  for (const Scene& scene : {small_cavity(), small_channel()}) {
    RunOptions o;
    o.write_output = false;
    o.progress = false;
    o.threads = 1;
    const RunResult one = Simulation(scene, o).run();
    o.threads = 2;
    const RunResult two = Simulation(scene, o).run();
    EXPECT_EQ(hex64(one.state_hash), hex64(two.state_hash)) << scene.name;
  }
}

// Runs `scene`, which must stop after its first step with a guard message holding every one of `parts`.
static void expect_stop_after_first_step(const Scene& scene, std::initializer_list<const char*> parts) {
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  Simulation sim(scene, o);
  try {
    sim.run();
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const char* part : parts) EXPECT_NE(msg.find(part), std::string::npos) << msg;
  }
  EXPECT_EQ(sim.step(), 1);
}

TEST(FluidScene, PicardFailureStopsTheRunWithADiagnosis) {
  expect_stop_after_first_step(
      small_cavity({"fluid.on_picard_failure=stop"}),
      {"run stopped by the fluid guard", "did not converge in step 1", "fluid.picard_max_iterations"});
}

TEST(FluidScene, NonFiniteStateStopsTheRunWithADiagnosis) {
  // An inlet pressure at the edge of double range overflows in the first step.
  expect_stop_after_first_step(
      load_scene(kScenes + "validation/poiseuille.yaml",
                 {"fluid.boundaries[0].value=1.0e308", "mesh.generate.cells=[4, 2, 1]", "time.end=3"}),
      {"run stopped by the fluid guard", "non-finite velocity or pressure after step 1 (t = 1 s)",
       "What to change"});
}

TEST(FluidScene, ParabolicVelocityInlet) {
  // The channel driven by a parabolic inlet (peak 1 m/s) instead of the pressure: inlet nodes carry
  // 4 y (1 - y) after a step, the walls' corners 0.
  const Scene scene = load_scene(kScenes + "validation/poiseuille.yaml",
                                 {"fluid.boundaries[0]={surface: xmin, type: velocity, direction: [1, 0, 0], "
                                  "parabolic: [y]}",
                                  "mesh.generate.cells=[8, 4, 1]", "time.end=1"});
  EXPECT_TRUE(scene.fluid->boundaries[0].parabolic[1]);
  EXPECT_FALSE(scene.fluid->boundaries[0].parabolic[0]);
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  Simulation sim(scene, o);
  sim.run();
  const auto& fluid = dynamic_cast<const FluidModel&>(*sim.world().models[0]).solver();
  const auto x = fluid.nodes();
  const auto u = fluid.velocity();
  int inlet = 0;
  for (size_t n = 0; n < fluid.node_count(); ++n) {
    if (x[3 * n] != 0.0) continue;
    ++inlet;
    const double y = x[3 * n + 1];
    // ymin/ymax (no slip) come after xmin in the list and win on the shared edge nodes.
    const double want = (y == 0.0 || y == 1.0) ? 0.0 : 4.0 * y * (1.0 - y);
    EXPECT_NEAR(u[3 * n], want, 1e-14) << "y = " << y;
    EXPECT_EQ(u[3 * n + 1], 0.0);
  }
  EXPECT_EQ(inlet, 5 * 2);
  // A profile across an axis the surface is flat along is an error naming the key.
  try {
    Simulation bad(load_scene(kScenes + "validation/poiseuille.yaml",
                              {"fluid.boundaries[0]={surface: xmin, type: velocity, direction: [1, 0, 0], "
                               "parabolic: [x]}"}),
                   o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("fluid.boundaries[0].parabolic: surface 'xmin' has no extent along x"),
        std::string::npos)
        << e.what();
  }
}
