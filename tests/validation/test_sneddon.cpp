// Sneddon's pressurised crack in plane strain (scenes/validation/sneddon_plane_strain.yaml): an initial
// crack of half-length a whose faces carry solid.fracture.crack_pressure, relaxed to rest by mass damping.
// Analytic (shared/reference/fluid.md 3.1): w(x) = (4 p / E') sqrt(a^2 - x^2), E' = E / (1 - nu^2),
// w0 = 4 p a / E' = 3.75e-4 m and V = 2 pi p a^2 / E' = 5.89049e-4 m^2 per unit thickness (E = 10 GPa,
// nu = 0.25, a = 1 m, p = 1 MPa).
#include <cmath>
#include <map>
#include <numbers>

#include "systems/solid_tables.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift::validation {
namespace {

constexpr double kA = 1.0, kP = 1.0e6, kE = 1.0e10, kNu = 0.25, kThickness = 0.125;
const double kEPrime = kE / (1.0 - kNu * kNu);
const double kW0 = 4.0 * kP * kA / kEPrime;
const double kVolume = 2.0 * std::numbers::pi * kP * kA * kA / kEPrime;  // per unit thickness, both halves

struct CrackResult {
  std::map<long, double> opening;  // by node x in units of 1e-9 m: mean upper minus mean lower copy [m]
  double w0 = 0.0;                 // opening at x = 0
  double volume = 0.0;             // per unit thickness, both halves: 2 x trapezoid of w over [0, a]
  double metric_volume = 0.0;      // solid_crack_volume / thickness x 2 (opening x area over the joints)
  double volume_at_three_quarters = 0.0;  // the same at 3/4 of the run: how settled the end state is
  double external_work = 0.0, elastic = 0.0, joint = 0.0, balance = 0.0;
};

// The crack's opening from the node copies on y = 0: every tet corner there moves with its tet, so the
// mean displacement of the copies of tets above minus those below is the opening at that point.
std::map<long, double> crack_opening(Simulation& sim) {
  const Store& store = sim.world().store;
  const auto x0 = store.table(solid::node_table).span<const double>("x0");
  const auto x = store.table(solid::node_table).span<const double>("x");
  const auto conn = store.table(solid::tet_table).span<const int32_t>("nodes");
  std::map<long, std::array<double, 4>> sums;  // upper sum, upper count, lower sum, lower count
  for (size_t e = 0; e < conn.size() / 4; ++e) {
    double cy = 0.0;
    for (int k = 0; k < 4; ++k) cy += 0.25 * x0[3 * conn[4 * e + k] + 1];
    for (int k = 0; k < 4; ++k) {
      const size_t n = static_cast<size_t>(conn[4 * e + k]);
      if (std::abs(x0[3 * n + 1]) > 1e-9 || x0[3 * n] > kA + 1e-9) continue;
      auto& s = sums[std::lround(x0[3 * n] * 1e9)];
      const int side = cy > 0 ? 0 : 2;
      s[side] += x[3 * n + 1] - x0[3 * n + 1];
      s[side + 1] += 1.0;
    }
  }
  std::map<long, double> w;
  for (const auto& [key, s] : sums) w[key] = s[0] / s[1] - s[2] / s[3];
  return w;
}

CrackResult run_sneddon(int cells_per_a, int threads) {
  const int n = cells_per_a;
  // The fracture zone is one layer of cells on each side of the crack at every resolution (every tet that
  // touches the crack must be in it), so the band of intact joints around the crack thins with h.
  const std::string band = std::to_string(0.9 * kA / n);
  Scene scene = validation_scene(
      "sneddon_plane_strain.yaml",
      {"mesh.generate.cells=[" + std::to_string(10 * n) + ", " + std::to_string(20 * n) + ", 1]",
       "solid.fracture.box_min=[-1, -" + band + ", -1]", "solid.fracture.box_max=[1.25, " + band + ", 1]"});
  CrackResult r;
  run_watching(scene, threads, [&](Simulation& sim) {
    const int64_t step = sim.step(), total = sim.total_steps();
    if (step != 3 * total / 4 && step != total) return;
    Metrics m(solid_of(sim));
    m.update(sim.time());
    if (step == 3 * total / 4) {
      r.volume_at_three_quarters = 2.0 * m["solid_crack_volume"] / kThickness;
      return;
    }
    r.opening = crack_opening(sim);
    r.w0 = r.opening.begin()->second;
    double prev_x = 0.0, prev_w = r.w0;
    for (const auto& [key, w] : r.opening) {
      const double xk = static_cast<double>(key) * 1e-9;
      r.volume += (xk - prev_x) * (w + prev_w);  // 2 x trapezoid
      prev_x = xk, prev_w = w;
    }
    r.volume += (kA - prev_x) * prev_w;  // to the tip, where the opening is zero
    r.metric_volume = 2.0 * m["solid_crack_volume"] / kThickness;
    r.external_work = m["solid_external_work"];
    r.elastic = m["solid_elastic_energy"];
    r.joint = m["solid_joint_energy"];
    r.balance = m["solid_energy_balance_error"];
  });
  return r;
}

double relative(double value, double reference) {
  return value / reference - 1.0;
}

// 8 cells per half-length, the resolution fluid.md 3.8 asks 5 % of. Measured: w0 +2.6 %, V +0.9 %.
// The bound 5 % covers the linear tets' error at the tip (the opening goes as sqrt(a - x) there),
// the joints' own compliance (penalty 10 E in the layer around the crack), and the finite plate (10 a
// from the crack to every free edge: Feddersen's width factor sqrt(sec(pi a / W)) is 1.006 at a / W =
// 0.05).
TEST(Sneddon, PlaneStrainCrackOpensAsSneddonAt8CellsPerHalfLength) {
  const CrackResult fine = run_sneddon(8, 2);
  EXPECT_NEAR(relative(fine.w0, kW0), 0.0, 0.05) << "w0 = " << fine.w0 << " m, Sneddon " << kW0;
  EXPECT_NEAR(relative(fine.volume, kVolume), 0.0, 0.05)
      << "V = " << fine.volume << " m^2, Sneddon " << kVolume;
  // The profile: every node of the crack within 5 % of w0 of the ellipse. Not the tip node: the joints
  // there are intact, and they open by their own compliance under the tip's stress concentration
  // (measured 8 % of w0 at 8 cells, penalty 10 E), where the analytic opening is zero.
  for (const auto& [key, w] : fine.opening) {
    const double xk = static_cast<double>(key) * 1e-9;
    if (xk > kA - 1e-6) continue;
    EXPECT_NEAR(w, kW0 * std::sqrt(std::max(0.0, 1.0 - xk * xk / (kA * kA))), 0.05 * kW0) << "x = " << xk;
  }
  // The time series' crack volume (joint opening x area) is the same volume seen through the joints.
  EXPECT_NEAR(relative(fine.metric_volume, fine.volume), 0.0, 0.01);
  // Settled: the volume moved by less than 0.5 % over the last quarter of the run (0.22 % measured; the
  // relaxation is exponential, so what remains is below that: 10 x under the bound above).
  EXPECT_NEAR(relative(fine.volume_at_three_quarters, fine.metric_volume), 0.0, 5e-3);
  // Clapeyron: at rest under a constant pressure applied from t = 0, the stored energy is half the work
  // (the other half went into the damping). 1 % covers what is still settling and the balance error.
  EXPECT_NEAR((fine.elastic + fine.joint) / fine.external_work, 0.5, 0.01);
  // And the work is p times the opened volume (half model, thickness t): p V t / 2.
  EXPECT_NEAR(relative(fine.external_work, kP * fine.metric_volume * kThickness / 2.0), 0.0, 0.01);

  // Refinement: at 4 cells per half-length both errors are larger (measured w0 -4.2 %, V -9.9 %).
  const CrackResult coarse = run_sneddon(4, 2);
  EXPECT_GT(std::abs(relative(coarse.w0, kW0)), std::abs(relative(fine.w0, kW0)));
  EXPECT_GT(std::abs(relative(coarse.volume, kVolume)), std::abs(relative(fine.volume, kVolume)));
  RecordProperty("w0_error_4", relative(coarse.w0, kW0));
  RecordProperty("w0_error_8", relative(fine.w0, kW0));
  std::printf("Sneddon: 4 cells per a: w0 %+.4f, V %+.4f; 8 cells: w0 %+.4f, V %+.4f\n",
              relative(coarse.w0, kW0), relative(coarse.volume, kVolume), relative(fine.w0, kW0),
              relative(fine.volume, kVolume));
}

}  // namespace
}  // namespace rift::validation
