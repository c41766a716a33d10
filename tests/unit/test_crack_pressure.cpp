// solid.fracture.crack_pressure (a pressure on the faces of broken joints) and solid.mass_damping (a drag
// on every node, for relaxation to rest): who is pressed and when, the energy books, restart and
// threads. The Sneddon opening itself is checked in tests/validation/test_sneddon.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/validation_support.hpp"

using namespace rift;
namespace fs = std::filesystem;

namespace {

// The Sneddon scene at 4 cells per half-length (19,200 tets; the zone one cell layer on each side of the
// crack), cut to a few hundred steps.
Scene small_sneddon(std::vector<std::string> more = {}) {
  std::vector<std::string> o{"mesh.generate.cells=[40, 80, 1]", "solid.fracture.box_min=[-1, -0.225, -1]",
                             "solid.fracture.box_max=[1.25, 0.225, 1]", "time.end=1.5e-3",
                             "output.interval=5.0e-4"};
  o.insert(o.end(), more.begin(), more.end());
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/sneddon_plane_strain.yaml", o);
}

std::unique_ptr<Simulation> start(const Scene& scene, int threads = 1) {
  RunOptions o;
  o.threads = threads;
  o.progress = false;
  o.write_output = false;
  return std::make_unique<Simulation>(scene, o);
}

using validation::solid_of;

// Sum of |corner force| over the crack faces of intact and of broken joints.
std::pair<double, double> crack_face_forces(Simulation& sim, size_t first_crack_face) {
  const Store& store = sim.world().store;
  const auto broken = store.table(solid::joint_table).span<const uint8_t>("broken");
  const auto force = store.table(solid::face_table).span<const double>("corner_force");
  double intact = 0.0, pressed = 0.0;
  for (size_t j = 0; j < broken.size(); ++j)
    for (size_t c = 0; c < 18; ++c)
      (broken[j] ? pressed : intact) += std::abs(force[9 * first_crack_face + 18 * j + c]);
  return {intact, pressed};
}

}  // namespace

TEST(CrackPressure, PressesTheFacesOfBrokenJointsOnlyAndOpensTheCrack) {
  auto sim = start(small_sneddon());
  const size_t joints = sim->world().store.table(solid::joint_table).size();
  const size_t faces = sim->world().store.table(solid::face_table).size();
  ASSERT_GE(faces, 2 * joints);
  const size_t first = faces - 2 * joints;  // the joint faces come after the boundary faces
  for (int i = 0; i < 50; ++i) sim->step_once();
  const auto [intact, pressed] = crack_face_forces(*sim, first);
  EXPECT_EQ(intact, 0.0);
  // 8 broken joints (4 cells x 2 triangles), 2 faces each: the force on them is p x their area.
  const auto area = sim->world().store.table(solid::event_table).span<const double>("area");
  double total_area = 0.0;
  for (double a : area) total_area += a;
  EXPECT_EQ(area.size(), 8u);
  // Each face's three corner forces add up to p A along the normal: |f| summed over components is at
  // least p A (all along y here, to the rotation of the face).
  EXPECT_NEAR(pressed, 2.0 * 1.0e6 * total_area, 1e-3 * pressed);
  nlohmann::json summary;
  solid_of(*sim).summarize(summary);
  EXPECT_EQ(summary["solid"]["crack_faces_pressed"], 16);
  // The crack opens: the volume between its faces grows, and the pressure's work is external work.
  std::vector<std::pair<std::string, double>> row;
  solid_of(*sim).metrics(sim->time(), row);
  double volume = -1.0, pressure = -1.0;
  for (const auto& [k, v] : row) {
    if (k == "solid_crack_volume") volume = v;
    if (k == "solid_crack_pressure") pressure = v;
  }
  EXPECT_GT(volume, 0.0);
  EXPECT_EQ(pressure, 1.0e6);
  const SolidEnergies e = solid_of(*sim).energies();
  EXPECT_GT(e.external_work, 0.0);
  // 5 %, the bound of the stability tests: the pressure is a step at t = 0, whose first steps the
  // central difference books to O(dt) (3 % after 50 steps here; the full Sneddon run ends at 1e-8).
  EXPECT_LT(std::abs(e.balance_error()), 0.05 * e.external_work);
}

TEST(InitialCracks, ACrackThatTetsOutsideTheZoneTouchIsAnError) {
  // A zone of only the tets with a face on the crack: the tets above and below that touch the crack by
  // an edge or a vertex share its nodes and would hold it shut.
  try {
    start(small_sneddon(
        {"solid.fracture.box_min=[-1, -0.075, -1]", "solid.fracture.box_max=[1.25, 0.075, 1]"}));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("held shut"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("solid.fracture.box_min"), std::string::npos) << e.what();
  }
}

TEST(CrackPressure, AJointThatBreaksIsPressedFromTheNextStep) {
  // Weak joints: the pressure at the crack tips breaks the ligament, and every new break is pressed.
  auto sim = start(small_sneddon(
      {"solid.materials[0].fracture.tensile_strength=2.0e6", "solid.materials[0].fracture.cohesion=4.0e6",
       "solid.materials[0].fracture.G_I=1", "solid.materials[0].fracture.G_II=1"}));
  for (int i = 0; i < 300; ++i) sim->step_once();
  const size_t broken = sim->world().store.table(solid::event_table).size();
  ASSERT_GT(broken, 8u) << "the crack did not grow";
  sim->step_once();
  nlohmann::json summary;
  solid_of(*sim).summarize(summary);
  EXPECT_EQ(summary["solid"]["crack_faces_pressed"].get<size_t>(),
            2 * sim->world().store.table(solid::event_table).size());
}

TEST(CrackPressure, RestartAndThreadsGiveTheSameBits) {
  const Scene scene = small_sneddon(
      {"solid.materials[0].fracture.tensile_strength=2.0e6", "solid.materials[0].fracture.cohesion=4.0e6"});
  const test::TempDir dir;
  const fs::path a = dir.path() / "straight", b = dir.path() / "restarted", c = dir.path() / "two_threads";
  const RunResult straight = test::run_scene(scene, a, 1);
  ASSERT_TRUE(straight.completed);
  test::run_scene(scene, b, 1, straight.steps / 2);
  const RunResult restarted = test::run_scene(scene, b, 1, std::nullopt, true);
  EXPECT_EQ(hex64(restarted.state_hash), hex64(straight.state_hash));
  const RunResult two = test::run_scene(scene, c, 2);
  EXPECT_EQ(hex64(two.state_hash), hex64(straight.state_hash));
}

TEST(MassDamping, RigidMotionDecaysAsTheDampedLeapfrogAndTheEnergyIsBooked) {
  // Two blocks flying apart (no contact before 1e-4 s): each moves rigidly, so the only force is the drag,
  // and every step multiplies the velocity by (1 - c dt / 2) / (1 + c dt / 2).
  const double c = 2000.0;
  Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/contact_collision.yaml",
                           {"solid.mass_damping=2000", "solid.initial_velocity[0].velocity=[-1.5, 0, 0]",
                            "solid.initial_velocity[1].velocity=[0.5, 0, 0]"});
  auto sim = start(scene);
  const int steps = 200;
  for (int i = 0; i < steps; ++i) sim->step_once();
  const double dt = sim->time() / steps;
  const double keep = (1.0 - 0.5 * c * dt) / (1.0 + 0.5 * c * dt);
  const auto v = sim->world().store.table(solid::node_table).span<const double>("v");
  double worst = 0.0;
  const double expected_right = 0.5 * std::pow(keep, steps);
  for (size_t i = 0; i < v.size(); i += 3)
    if (v[i] > 0) worst = std::max(worst, std::abs(v[i] / expected_right - 1.0));
  EXPECT_LT(worst, 1e-9);  // round-off of the rigid motion's strain only
  EXPECT_NEAR(std::pow(keep, steps), std::exp(-c * sim->time()), 1e-3);  // the drag's exact decay, to O(dt^2)
  const SolidEnergies e = solid_of(*sim).energies();
  EXPECT_GT(e.damping, 0.0);
  // The initial kinetic energy counts as external work: it is now kinetic energy or dissipated.
  EXPECT_LT(std::abs(e.balance_error()), 1e-9 * e.external_work);
}

TEST(MassDamping, AScheduleDampsUntilItEndsAndThenKeepsTheMotion) {
  // The same rigid flight with the drag on for the first 100 steps only (a table that drops to 0): the
  // velocity decays by keep^100 and then stays, and the booked dissipation stops growing with it.
  const double c = 2000.0;
  Scene scene = load_scene(
      std::string(RIFT_SOURCE_DIR) + "/scenes/validation/contact_collision.yaml",
      {"solid.initial_velocity[0].velocity=[-1.5, 0, 0]", "solid.initial_velocity[1].velocity=[0.5, 0, 0]"});
  auto probe = start(scene);
  probe->step_once();
  const double dt = probe->time();
  const double t_off = 99.5 * dt;  // steps 0..99 start before it (damped), step 100 on after (undamped)
  scene.solid->mass_damping.kind = TimeFunction::Kind::table;
  scene.solid->mass_damping.points = {{0.0, c}, {t_off - 1e-3 * dt, c}, {t_off, 0.0}};
  auto sim = start(scene);
  for (int i = 0; i < 100; ++i) sim->step_once();
  const double damping_at_off = solid_of(*sim).energies().damping;
  for (int i = 0; i < 100; ++i) sim->step_once();
  const double keep = (1.0 - 0.5 * c * dt) / (1.0 + 0.5 * c * dt);
  const auto v = sim->world().store.table(solid::node_table).span<const double>("v");
  const double expected_right = 0.5 * std::pow(keep, 100);
  double worst = 0.0;
  for (size_t i = 0; i < v.size(); i += 3)
    if (v[i] > 0) worst = std::max(worst, std::abs(v[i] / expected_right - 1.0));
  EXPECT_LT(worst, 1e-9);
  const SolidEnergies e = solid_of(*sim).energies();
  EXPECT_GT(damping_at_off, 0.0);
  EXPECT_EQ(e.damping, damping_at_off);
  EXPECT_LT(std::abs(e.balance_error()), 1e-9 * e.external_work);
}
