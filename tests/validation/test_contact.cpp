// Contact validation (issue 4): the scenes scenes/validation/contact_*.yaml run through the Simulation the
// CLI uses. Each tolerance is stated with the reason it is fair.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "engine/core/state_hash.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

// Mass, centre of mass and momentum of the nodes of one mesh region.
struct BodyState {
  double mass = 0.0, com[3] = {0, 0, 0}, momentum[3] = {0, 0, 0};
};

std::vector<int32_t> region_nodes(Simulation& sim, const std::string& region) {
  const int32_t r = sim.world().mesh.region_index(region);
  EXPECT_GE(r, 0) << region;
  const Table& tets = sim.world().store.table(solid::tet_table);
  const auto conn = tets.span<const int32_t>("nodes");
  const auto reg = tets.span<const int32_t>("region");
  std::set<int32_t> nodes;
  for (size_t e = 0; e < tets.size(); ++e)
    if (reg[e] == r)
      for (int k = 0; k < 4; ++k) nodes.insert(conn[4 * e + k]);
  return {nodes.begin(), nodes.end()};
}

BodyState body_state(Simulation& sim, const std::vector<int32_t>& nodes) {
  const Table& t = sim.world().store.table(solid::node_table);
  const auto x = t.span<const double>("x");
  const auto v = t.span<const double>("v");
  const auto m = t.span<const double>("mass");
  BodyState s;
  for (int32_t n : nodes) {
    s.mass += m[n];
    for (int c = 0; c < 3; ++c) {
      s.com[c] += m[n] * x[3 * n + c];
      s.momentum[c] += m[n] * v[3 * n + c];
    }
  }
  for (double& c : s.com) c /= s.mass;
  return s;
}

// Mean axial (zz) stress of the tets whose reference centroid passes `inside`.
template <class Inside>
double mean_axial_stress(Simulation& sim, Inside inside) {
  const Table& tets = sim.world().store.table(solid::tet_table);
  const auto conn = tets.span<const int32_t>("nodes");
  const auto x0 = sim.world().store.table(solid::node_table).span<const double>("x0");
  const auto stress = tets.span<const double>("stress");
  double s = 0.0;
  int count = 0;
  for (size_t e = 0; e < tets.size(); ++e) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) c[i] += 0.25 * x0[3 * conn[4 * e + k] + i];
    if (inside(c)) s += stress[6 * e + 2], ++count;
  }
  return s / count;
}

// 1. Incline. a = g (sin theta - mu cos theta) = 2.356 m/s^2 at 30 degrees, mu = 0.3. The acceleration is
// measured between t = 0.04 s and the end (0.1 s), after the drop onto the plate has settled, as the slope
// of the block's mean velocity (momentum / mass) fitted by least squares. 2 % (the bound): the
// friction force of a sliding block is exactly mu N at every instant, so only the time average of N enters,
// and it equals m g cos theta once the normal oscillation has decayed; what remains is the lattice's small
// rocking (a 2 x 2 x 2 block).
TEST(ContactValidation, BlockSlidesDownTheInclineAtGSinMinusMuCos) {
  const Scene scene = validation_scene("contact_incline.yaml");
  const double g = 9.81, theta = 30.0 * M_PI / 180.0, mu = 0.3;
  const double expected = g * (std::sin(theta) - mu * std::cos(theta));
  std::vector<int32_t> block;
  // Least-squares slope of v(t) over the window: the normal and rocking oscillations average out instead
  // of entering through two end points.
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (block.empty()) block = region_nodes(sim, "block");
    const BodyState s = body_state(sim, block);
    // v at t - dt/2 (the leapfrog's velocity), so its time is t - dt/2.
    const double t = sim.time() - 0.5 * sim.dt(), v = s.momentum[0] / s.mass;
    if (t < 0.04) return;
    n += 1, st += t, sv += v, stt += t * t, stv += t * v;
  });
  const double a = (n * stv - st * sv) / (n * stt - st * st);
  RecordProperty("incline_acceleration", testing::PrintToString(a));
  RecordProperty("incline_expected", testing::PrintToString(expected));
  EXPECT_NEAR(a / expected, 1.0, 0.02) << "a = " << a << " m/s^2, expected " << expected;
}

// Below the friction angle (10 < 16.7 degrees) the block sticks. Bound on the drift: the friction springs
// carry m g sin theta with a deflection of m g sin theta / (sum of k_t over the touching pairs), a few
// micrometres here, plus the block's shear strain; a creeping block would instead move like the frictionless
// one, g sin theta t^2 / 2 = 8.5 mm in 0.1 s. The test allows 1 % of that over the last 60 ms (85 um),
// and asks for a velocity at the end below 1 % of g sin theta x 0.1 s.
TEST(ContactValidation, BlockSticksBelowTheFrictionAngle) {
  const double g = 9.81, theta = 10.0 * M_PI / 180.0;
  const Scene scene =
      validation_scene("contact_incline.yaml", {"solid.gravity=[" + std::to_string(g * std::sin(theta)) +
                                                ", 0, " + std::to_string(-g * std::cos(theta)) + "]"});
  std::vector<int32_t> block;
  double x1 = NAN, x2 = 0.0, v_end = 0.0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (block.empty()) block = region_nodes(sim, "block");
    const BodyState s = body_state(sim, block);
    if (std::isnan(x1) && sim.time() >= 0.04) x1 = s.com[0];
    x2 = s.com[0];
    v_end = s.momentum[0] / s.mass;
  });
  const double free_slide = 0.5 * g * std::sin(theta) * 0.1 * 0.1;
  RecordProperty("stick_drift_m", testing::PrintToString(x2 - x1));
  EXPECT_LT(std::abs(x2 - x1), 0.01 * free_slide);
  EXPECT_LT(std::abs(v_end), 0.01 * g * std::sin(theta) * 0.1);
}

// The incline over angles, friction coefficients and meshes: the corners of the study in
// bench/contact_incline_study.py (docs/validation.md has the whole grid) and the cases that a damping
// not proportional to each pair's stiffness gets wrong (45 and 60 degrees at mu = 0.8 on 2 and 4 cells:
// 5 - 8 % fast, or stopped by the contact guard), and 45 degrees / mu 0.8 on 4 cells, near tipping, which
// a friction cap that included the dashpot's force put off by -2 to +6 % as the step changed (+3.9 % at
// time.safety 0.25, the case here, by this fit; the study reads +0.6 % with the cap on the potential's normal
// force). Sliding: the acceleration within 2 % of g (sin - mu cos) (the bound; friction is mu N at
// every instant of a slide, so only the time average of N enters). Sticking: the drift of the centre, its
// mean over the last 10 ms less that over 40 - 50 ms (means, so that the elastic ringing left from the drop
// does not count), below 1e-6 of the block (20 nm). Both: contact never puts energy in, its stored energy
// (work done on the contact less friction and damping) staying above -1e-3 of the friction dissipation (the
// central difference's O(dt) share of that work).
struct InclineCase {
  double theta_deg, mu;
  int n;                // cells per side, or the block's edge over the element size
  bool unstructured;    // CGAL Mesh_3 block instead of the Kuhn lattice
  double safety = 0.5;  // time.safety (the scene's 0.5)
};

class InclineGrid : public testing::TestWithParam<InclineCase> {};

TEST_P(InclineGrid, SlidesAtGSinMinusMuCosOrSticks) {
  const InclineCase c = GetParam();
  const double g = 9.81, theta = c.theta_deg * M_PI / 180.0, block_edge = 0.02;
  std::vector<std::string> sets = {"solid.gravity=[" + std::to_string(g * std::sin(theta)) + ", 0, " +
                                       std::to_string(-g * std::cos(theta)) + "]",
                                   "solid.contact.friction=" + std::to_string(c.mu),
                                   "time.safety=" + std::to_string(c.safety)};
  const std::string n = std::to_string(c.n);
  sets.push_back(c.unstructured
                     ? "mesh.generate.blocks[1]={name: block, origin: [-0.01, -0.01, 0.0], size: [0.02, "
                       "0.02, 0.02], element_size: " +
                           std::to_string(block_edge / c.n) + "}"
                     : "mesh.generate.blocks[1].cells=[" + n + ", " + n + ", " + n + "]");
  const Scene scene = validation_scene("contact_incline.yaml", sets);
  std::vector<int32_t> block;
  double k = 0, st = 0, sv = 0, stt = 0, stv = 0, least_stored = 0, friction = 0;
  double x_early = 0, n_early = 0, x_late = 0, n_late = 0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (block.empty()) block = region_nodes(sim, "block");
    const BodyState s = body_state(sim, block);
    if (sim.step() % 64 == 0 || sim.step() == sim.total_steps()) {
      const SolidEnergies e = solid_of(sim).energies();
      least_stored = std::min(least_stored, e.contact_stored);
      friction = e.friction;
    }
    const double t = sim.time() - 0.5 * sim.dt(), v = s.momentum[0] / s.mass;
    if (sim.time() < 0.04) return;
    if (sim.time() < 0.05) x_early += s.com[0], n_early += 1;
    if (sim.time() >= 0.09) x_late += s.com[0], n_late += 1;
    k += 1, st += t, sv += v, stt += t * t, stv += t * v;
  });
  const bool slides = std::tan(theta) > c.mu;
  if (slides) {
    const double a = (k * stv - st * sv) / (k * stt - st * st);
    const double expected = g * (std::sin(theta) - c.mu * std::cos(theta));
    RecordProperty("acceleration_rel_error", testing::PrintToString(a / expected - 1));
    EXPECT_NEAR(a / expected, 1.0, 0.02) << "a = " << a << " m/s^2, expected " << expected;
  } else {
    const double drift = x_late / n_late - x_early / n_early;
    RecordProperty("drift_m", testing::PrintToString(drift));
    EXPECT_LT(std::abs(drift), 1e-6 * block_edge);
  }
  RecordProperty("least_contact_stored_over_friction", testing::PrintToString(least_stored / friction));
  EXPECT_GT(least_stored, -1e-3 * friction);
}

INSTANTIATE_TEST_SUITE_P(ContactValidation, InclineGrid,
                         testing::Values(InclineCase{5, 0.1, 1, false}, InclineCase{5, 0.8, 2, false},
                                         InclineCase{60, 0.1, 3, false}, InclineCase{60, 0.8, 4, false},
                                         InclineCase{45, 0.8, 2, false}, InclineCase{30, 0.5, 3, true},
                                         InclineCase{20, 0.3, 2, true}, InclineCase{10, 0.8, 3, true},
                                         InclineCase{45, 0.8, 4, false, 0.25}),
                         [](const testing::TestParamInfo<InclineCase>& i) {
                           return std::to_string(static_cast<int>(i.param.theta_deg)) + "deg_mu" +
                                  std::to_string(static_cast<int>(std::lround(i.param.mu * 10))) + "_" +
                                  (i.param.unstructured ? "unstructured" : "lattice") +
                                  std::to_string(i.param.n) +
                                  (i.param.safety != 0.5
                                       ? "_safety" + std::to_string(std::lround(100 * i.param.safety))
                                       : "");
                         });

// 2. Head-on collision. Momentum: every contact force is applied with its opposite and the tets' internal
// forces sum to zero, so the total momentum changes only by round-off: 1e-10 relative to the initial
// |p| (round-off per step ~1e-16 of the largest nodal momentum, over ~5000 steps). Energy: Munjiza's
// potential is conservative, so kinetic + elastic after separation is within 1 % of the initial kinetic
// energy (the rest is the central difference and the deforming-tet error of the potential).
TEST(ContactValidation, HeadOnCollisionConservesMomentumAndEnergy) {
  const Scene scene = validation_scene("contact_collision.yaml");
  std::vector<int32_t> all;
  double p0 = NAN, e0 = NAN, worst_dp = 0.0, e_end = 0.0;
  size_t touched = 0, touching_end = 1;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (all.empty()) {
      for (const char* r : {"left", "right"})
        for (int32_t n : region_nodes(sim, r)) all.push_back(n);
    }
    const BodyState s = body_state(sim, all);
    SolidModel& solid = solid_of(sim);
    const SolidEnergies e = solid.energies();
    if (std::isnan(p0)) p0 = s.momentum[0], e0 = e.kinetic;
    worst_dp =
        std::max(worst_dp, std::abs(s.momentum[0] - p0) + std::abs(s.momentum[1]) + std::abs(s.momentum[2]));
    Metrics m(solid);
    m.update(sim.time());
    touching_end = static_cast<size_t>(m["contact_touching"]);
    touched = std::max(touched, touching_end);
    e_end = e.kinetic + e.elastic;
  });
  RecordProperty("momentum_error", testing::PrintToString(worst_dp / std::abs(p0)));
  RecordProperty("energy_ratio", testing::PrintToString(e_end / e0));
  EXPECT_GT(touched, 0u) << "the blocks never touched";
  EXPECT_EQ(touching_end, 0u) << "the blocks have not separated by the end";
  EXPECT_LT(worst_dp / std::abs(p0), 1e-10);
  EXPECT_NEAR(e_end / e0, 1.0, 0.01);
}

// 3. A column cut by an initial crack. Quasi-static once the load is held: the base reaction equals the
// applied 40 N, averaged over the last 4 ms to remove the decaying oscillation of the column on its contact
// springs (window >> its period, so the residual of the average is < 0.5 %). 2 % (the bound).
// The axial stress in the two layers of tets touching the cut is checked too: it can only get there
// through contact.
TEST(ContactValidation, CutColumnCarriesCompressionAcrossTheCrack) {
  const Scene scene = validation_scene("contact_cut_column.yaml");
  double sum = 0.0, stress_sum = 0.0;
  size_t n = 0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (sim.time() < 4e-3) return;
    SolidModel& solid = solid_of(sim);
    Metrics m(solid);
    m.update(sim.time());
    sum += m["solid_reaction_column_zmin_z"];
    stress_sum += mean_axial_stress(sim, [](const double* c) { return std::abs(c[2] - 0.02) < 0.01; });
    ++n;
  });
  const double reaction = sum / static_cast<double>(n), stress = stress_sum / static_cast<double>(n);
  RecordProperty("cut_reaction_N", testing::PrintToString(reaction));
  RecordProperty("cut_stress_Pa", testing::PrintToString(stress));
  EXPECT_NEAR(reaction / 40.0, 1.0, 0.02);
  EXPECT_NEAR(stress / -1e5, 1.0, 0.02);
}

// 3b. The same column with a crack over only the middle quarter of the section (a 4 x 4 x 8 lattice; the
// crack: the joints of the central 2 x 2 cells on z = 20 mm), so the crack's faces stay tied to the intact
// ring around them at its front. A crack normal to a uniform compression does not disturb it when its faces
// touch (they carry the normal stress, and there is no shear to slide them), so the tets over the crack
// carry the applied -100 kPa, within 2 % (as 3.: what is left of the load-up oscillation after averaging).
// This asks the contact to act between the two tets of each broken joint although they are still tied at
// the front: before 2026-12-02 such pairs were excluded, their faces sank into each other unresisted
// (no pair touching) and the load went round the crack through the ring (-72.6 kPa over it; now -99.8).
TEST(ContactValidation, PartialCrackCarriesCompressionWhileTiedAtItsFront) {
  const Scene scene = validation_scene(
      "contact_cut_column.yaml",
      {"mesh.generate.blocks[0].cells=[4, 4, 8]", "solid.fracture.initial_cracks[0].point=[0.01, 0.01, 0.02]",
       "solid.fracture.initial_cracks[0].radius=0.006"});
  double stress_sum = 0.0;
  size_t n = 0, touching = 0, cracked = 0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (sim.time() < 4e-3) return;
    SolidModel& solid = solid_of(sim);
    stress_sum += mean_axial_stress(sim, [](const double* c) {
      return std::abs(c[2] - 0.02) < 0.005 && std::abs(c[0] - 0.01) < 0.005 && std::abs(c[1] - 0.01) < 0.005;
    });
    ++n;
    Metrics m(solid);
    m.update(sim.time());
    touching = static_cast<size_t>(m["contact_touching"]);
    cracked = static_cast<size_t>(m["solid_broken_joints"]);
  });
  const double stress = stress_sum / static_cast<double>(n);
  RecordProperty("partial_crack_stress_Pa", testing::PrintToString(stress));
  EXPECT_EQ(cracked, 8u);
  EXPECT_EQ(touching, cracked);
  EXPECT_NEAR(stress / -1e5, 1.0, 0.02);
}

// Pulled instead of pushed: the crack opens. The upper half (all its nodes above the cut) moves away from
// the lower one by far more than the elastic stretch of an intact column under the same pull (sigma L / E
// = 1e5 x 0.04 / 1e8 = 40 um): it has nothing holding it.
TEST(ContactValidation, CutColumnSeparatesInTension) {
  const Scene scene = validation_scene(
      "contact_cut_column.yaml", {"solid.boundaries[1].value={ramp: {value: 0, start_time: 0, rate: -5.0e7, "
                                  "limit: -1.0e5}}",
                                  "time.end=4e-3"});
  double gap = 0.0;
  run_watching(scene, 1, [&](Simulation& sim) {
    const Table& tets = sim.world().store.table(solid::tet_table);
    const auto conn = tets.span<const int32_t>("nodes");
    const auto x = sim.world().store.table(solid::node_table).span<const double>("x");
    const auto x0 = sim.world().store.table(solid::node_table).span<const double>("x0");
    double lowest_upper = INFINITY, highest_lower = -INFINITY;
    for (size_t e = 0; e < tets.size(); ++e) {
      double zc = 0.0;
      for (int k = 0; k < 4; ++k) zc += 0.25 * x0[3 * conn[4 * e + k] + 2];
      for (int k = 0; k < 4; ++k) {
        const int32_t node = conn[4 * e + k];
        if (std::abs(x0[3 * node + 2] - 0.02) > 1e-9) continue;
        if (zc > 0.02)
          lowest_upper = std::min(lowest_upper, x[3 * node + 2]);
        else
          highest_lower = std::max(highest_lower, x[3 * node + 2]);
      }
    }
    gap = lowest_upper - highest_lower;
  });
  RecordProperty("cut_tension_gap_m", testing::PrintToString(gap));
  EXPECT_GT(gap, 10 * 40e-6);
}

// 4. Resting block. After settling (t > 0.05 s): along the plate the centre of mass moves by less than
// 1e-6 of the block's edge (20 nm): the Kuhn split is not mirror-symmetric, so the contact forces of a
// resting block have small tangential parts, which the friction springs carry with nanometre deflections; a
// creeping block would move micrometres or more. Its vertical jitter stays below the static compression
// itself (the sudden-gravity drop can at most double it; the damping has taken that out by then).
TEST(ContactValidation, RestingBlockNeitherDriftsNorJitters) {
  const Scene scene = validation_scene("contact_resting.yaml");
  std::vector<int32_t> block;
  double z0 = NAN, x_ref = NAN, y_ref = NAN, z_min = INFINITY, z_max = -INFINITY, drift = 0.0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (block.empty()) block = region_nodes(sim, "block");
    const BodyState s = body_state(sim, block);
    if (std::isnan(z0)) z0 = s.com[2];
    if (sim.time() < 0.05) return;
    if (std::isnan(x_ref)) x_ref = s.com[0], y_ref = s.com[1];
    drift = std::max(drift, std::hypot(s.com[0] - x_ref, s.com[1] - y_ref));
    z_min = std::min(z_min, s.com[2]);
    z_max = std::max(z_max, s.com[2]);
  });
  const double settle = z0 - 0.5 * (z_min + z_max);  // static compression of contact + block
  RecordProperty("resting_settlement_m", testing::PrintToString(settle));
  RecordProperty("resting_jitter_m", testing::PrintToString(z_max - z_min));
  RecordProperty("resting_drift_m", testing::PrintToString(drift));
  EXPECT_GT(settle, 0.0);
  EXPECT_LT(z_max - z_min, settle);
  EXPECT_LT(drift, 1e-6 * 0.02);
}

// 5. Determinism with active contacts: the sliding block (friction, damping, re-detections) on 1, 2 and 4
// threads ends in bitwise the same state.
TEST(ContactValidation, SameStateOnOneTwoAndFourThreads) {
  const Scene scene = validation_scene("contact_incline.yaml", {"time.end=0.02"});
  std::vector<uint64_t> hashes;
  for (int threads : {1, 2, 4}) {
    RunOptions o;
    o.threads = threads;
    o.progress = false;
    o.write_output = false;
    Simulation sim(scene, o);
    hashes.push_back(sim.run().state_hash);
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
}

// A step twice the contact estimate: the collision gains energy through the contact springs; the run must
// stop with the contact diagnosis (cause and remedy), not finish or write NaN.
TEST(ContactValidation, AStepAboveTheContactLimitStopsWithADiagnosis) {
  Scene scene = validation_scene("contact_collision.yaml", {"time.allow_unstable_dt=true"});
  double contact_dt = 0.0;
  {
    RunOptions o;
    o.progress = false;
    o.write_output = false;
    Simulation probe(scene, o);
    contact_dt = solid_of(probe).stable_dt();
  }
  scene.time.dt = 2.0 * contact_dt;
  const test::TempDir dir;
  try {
    test::run_scene(scene, dir.path(), 1);
    ADD_FAILURE() << "the run finished";
  } catch (const std::exception& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("contact is putting energy"), std::string::npos) << why;
    EXPECT_NE(why.find("solid.contact.penalty"), std::string::npos) << why;
  }
}

// Restart with active contacts: the pair list, the friction histories, the detection positions and the
// contact energy integrals go through the checkpoint; the grouping of node copies is rebuilt from the
// fracture log. Stopped mid-slide, restarted: bitwise the same end state as a straight run.
TEST(ContactValidation, RestartMidSlideIsBitwiseIdentical) {
  const Scene scene = validation_scene("contact_incline.yaml", {"time.end=0.02", "output.interval=0.005"});
  const test::TempDir dir;
  const auto a = dir.path() / "straight", b = dir.path() / "restarted";
  const RunResult straight = test::run_scene(scene, a, 2);
  ASSERT_TRUE(straight.completed);
  test::run_scene(scene, b, 1, straight.steps / 2);
  const RunResult second = test::run_scene(scene, b, 2, std::nullopt, true);
  EXPECT_EQ(hex64(second.state_hash), hex64(straight.state_hash));
}

}  // namespace
}  // namespace rift::validation
