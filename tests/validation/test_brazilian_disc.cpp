// Validation 4-6: the Brazilian disc (scenes/validation/brazilian_disc.yaml) at two mesh sizes: peak
// load against the elastic formula, a split along the loaded diameter, the energy balance over the
// fracturing run, and the same state hash on 1, 2 and 4 threads.
//
// Peak load band. The elastic (Hondros) solution gives sigma_t = 2 P / (pi D t) across the loaded
// diameter, so P_ref = pi D t f_t / 2 = 3.93 kN. FDEM with joints on the faces of an unstructured tet
// mesh overestimates it: the crack must open facets inclined to the principal direction, and femdem.md
// (section 2, item 10) gives 0.9 - 1.5 P_ref as the usual band for mesh and penalty dependence. A
// cohesive law adds a size effect: here l_ch = E G_I / f_t^2 = 16 mm, D / l_ch = 3.1, and cohesive
// Brazilian tests at that ratio report nominal strengths some 10-20 % above f_t (Rocco et al. 1999,
// from memory: [L] in femdem.md's terms). The accepted band is therefore 0.9 - 1.7 P_ref.
#include <cmath>

#include "engine/core/state_hash.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

constexpr double kD = 0.05, kT = 0.01, kFt = 5.0e6;
const double kReference = M_PI * kD * kT * kFt / 2.0;

struct DiscRun {
  double peak = 0.0;
  double external_work = 0.0, balance_error = 0.0;
  size_t broken = 0, tensile = 0;
  double area = 0.0, area_on_diameter = 0.0;  // broken joint area, and that with |x| < D / 8
  uint64_t hash = 0;
};

DiscRun run_disc(const std::vector<std::string>& overrides, int threads) {
  DiscRun r;
  const Scene scene = validation_scene("brazilian_disc.yaml", overrides);
  SolidModel* solid = nullptr;
  run_watching(scene, threads, [&](Simulation& sim) {
    solid = &solid_of(sim);
    if (sim.step() % 10 != 0) return;
    Metrics m(*solid);
    m.update(sim.time());
    r.peak = std::max(r.peak, -m["solid_reaction_load_top_y"]);
    if (sim.step() == sim.total_steps() - sim.total_steps() % 10 || sim.step() + 10 > sim.total_steps()) {
      const SolidEnergies e = solid->energies();
      r.external_work = e.external_work;
      r.balance_error = e.balance_error();
      const Table& events = sim.world().store.table("solid_fracture_event");
      r.broken = events.size();
      const auto mode = events.span<const uint8_t>("mode");
      const auto centroid = events.span<const double>("centroid");
      const auto area = events.span<const double>("area");
      r.tensile = 0, r.area = 0, r.area_on_diameter = 0;
      for (size_t k = 0; k < events.size(); ++k) {
        r.tensile += mode[k] == 1;
        r.area += area[k];
        if (std::abs(centroid[3 * k]) < kD / 8) r.area_on_diameter += area[k];
      }
      r.hash = state_hash(sim.world().store);
    }
  });
  return r;
}

void expect_split_disc(const DiscRun& r, const char* mesh) {
  SCOPED_TRACE(mesh);
  EXPECT_GE(r.peak / kReference, 0.9) << "peak " << r.peak << " N";
  EXPECT_LE(r.peak / kReference, 1.7) << "peak " << r.peak << " N";
  // The split runs along the loaded diameter (the x = 0 plane): most of the broken area lies within
  // D / 8 of it (the strip holds 31 % of the disc's area, so a scattered pattern would not pass), and
  // most breaks are tensile.
  ASSERT_GT(r.broken, 20u);
  EXPECT_GT(r.area_on_diameter / r.area, 0.6);
  EXPECT_GT(static_cast<double>(r.tensile) / r.broken, 0.6);
  // Validation 5: the energy balance closes to 1 % of the external work over the whole fracturing run.
  EXPECT_LT(std::abs(r.balance_error), 0.01 * r.external_work);
  ::testing::Test::RecordProperty(std::string(mesh) + "_peak_over_reference",
                                  std::to_string(r.peak / kReference));
  ::testing::Test::RecordProperty(std::string(mesh) + "_balance_error_over_work",
                                  std::to_string(r.balance_error / r.external_work));
  std::printf(
      "%s mesh: peak %.1f N = %.3f P_ref, %zu broken (%zu tensile), %.2f of the broken area within D/8 of "
      "the diameter, balance error %.3g of the external work\n",
      mesh, r.peak, r.peak / kReference, r.broken, r.tensile, r.area_on_diameter / r.area,
      r.balance_error / r.external_work);
}

TEST(BrazilianDisc, CoarseMeshSplitsAlongTheLoadedDiameter) {
  expect_split_disc(run_disc({}, 2), "3.3 mm");
}

TEST(BrazilianDisc, FineMeshSplitsAlongTheLoadedDiameter) {
  expect_split_disc(run_disc({"mesh.generate.size_min=0.0022", "mesh.generate.size_max=0.0022"}, 2),
                    "2.2 mm");
}

// Validation 6: the coarse disc up to just past the first breaks (the peak is near 2.7e-4 s), on 1, 2
// and 4 threads: every column of every table, fracture log included, hashes the same.
TEST(BrazilianDisc, SameStateOnOneTwoAndFourThreads) {
  const std::vector<std::string> shorter{"time.end=3.2e-4"};
  const DiscRun one = run_disc(shorter, 1), two = run_disc(shorter, 2), four = run_disc(shorter, 4);
  EXPECT_GT(one.broken, 0u);
  EXPECT_EQ(hex64(one.hash), hex64(two.hash));
  EXPECT_EQ(hex64(one.hash), hex64(four.hash));
}

}  // namespace
}  // namespace rift::validation
