// The fluid in the cracks (fracture_flow) against closed forms that nobody here chose.
//
// Sneddon by injection (scenes/validation/sneddon_injection.yaml): the plane-strain Griffith crack of
// test_sneddon.cpp, filled by injecting the volume V it holds at 1 MPa, V = 2 pi p a^2 / E'. With no
// viscosity the crack has one pressure, and the injected mass m = rho0 V takes the volume V / (1 + p / K_f)
// in the crack, so p (1 + p / K_f) = E' V / (2 pi a^2): 0.99955 MPa for water, 0.91608 MPa for K_f = 1e7 Pa
// (where the stiff answer would be 9 % off). The centre opening is Sneddon's w0 = 4 p a / E' at that p.
// The bound 5 % is the prescribed-pressure test's (test_sneddon.cpp): the linear tets' error at the tip,
// the joints' compliance and the finite plate; measured at 8 cells per half-length (the scene's graded
// lattice): p -0.47 % / -0.45 %, w0 +1.14 % / +1.18 % (water / K_f = 1e7 Pa).
// The books: fluid mass to 1e-12 of what was injected at every step; the pump's work equals the work on
// the rock plus the compression energy (no viscosity: no dissipation) to 1e-4 (measured 1.5e-6: the
// trapezoid rule of p dV over the steps).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

#include "engine/core/state_hash.hpp"
#include "systems/fracture_flow/fracture_flow_model.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/fracture_flow_support.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift {
namespace {

using validation::flow_of;
using validation::metric;
using validation::run_watching;
using validation::validation_scene;

constexpr double kE = 1.0e10, kNu = 0.25, kA = 1.0, kGI = 93.75;  // the KGD scenes' rock
const double kEp = kE / (1.0 - kNu * kNu);
constexpr double kInjected = 3.68156e-5 * 16.0;  // m^3 per metre of crack: the half model's x 2 / 0.125 m

struct InjectionResult {
  double pressure = 0, centre_aperture = 0, worst_mass_error = 0, pump = 0, work = 0, dissipation = 0,
         compression = 0;
};

InjectionResult run_injection(const std::vector<std::string>& overrides) {
  InjectionResult r;
  const Scene scene = validation_scene("sneddon_injection.yaml", overrides);
  run_watching(scene, 2, [&](Simulation& sim) {
    std::vector<std::pair<std::string, double>> row;
    flow_of(sim).metrics(sim.time(), row);
    const double injected = metric(row, "flow_injected_volume");
    if (injected > 0)
      r.worst_mass_error =
          std::max(r.worst_mass_error, std::abs(metric(row, "flow_mass_error")) / (1000.0 * injected));
    if (sim.step() != sim.total_steps()) return;
    r.pressure = metric(row, "flow_well_pressure");
    r.pump = metric(row, "flow_pump_work");
    r.work = metric(row, "flow_work_on_solid");
    r.dissipation = metric(row, "flow_dissipation");
    r.compression = metric(row, "flow_compression_energy");
    std::vector<XdmfGrid> grids;
    flow_of(sim).output_grids(grids, {"aperture"});
    // The crack's centre: the network point nearest x = 0 (the symmetry plane) at mid-thickness.
    const XdmfGrid& g = grids.at(0);
    double best = INFINITY;
    for (size_t p = 0; p < g.point_count; ++p) {
      const double d = std::abs(g.points[3 * p]) + std::abs(g.points[3 * p + 2] - 0.0625);
      if (d < best) {
        best = d;
        r.centre_aperture = static_cast<const double*>(g.fields.at(0).data)[p];
      }
    }
  });
  return r;
}

// p (1 + p / K_f) = E' V / (2 pi a^2), solved for p.
double sneddon_pressure(double bulk_modulus) {
  const double stiff = kEp * kInjected / (2.0 * M_PI * kA * kA);
  return 2.0 * stiff / (1.0 + std::sqrt(1.0 + 4.0 * stiff / bulk_modulus));
}

TEST(HydraulicFracture, SneddonByInjectionStiffAndSoftFluid) {
  for (double bulk : {2.2e9, 1.0e7}) {
    const InjectionResult r = run_injection({"fracture_flow.bulk_modulus=" + std::to_string(bulk)});
    const double p = sneddon_pressure(bulk);
    SCOPED_TRACE("K_f = " + std::to_string(bulk) + ", Sneddon's p = " + std::to_string(p));
    std::printf("Sneddon by injection, K_f = %.3g Pa: pressure %+.2f %%, centre opening %+.2f %%\n", bulk,
                100.0 * (r.pressure / p - 1.0), 100.0 * (r.centre_aperture / (4.0 * p * kA / kEp) - 1.0));
    EXPECT_NEAR(r.pressure / p, 1.0, 0.05) << r.pressure;
    EXPECT_NEAR(r.centre_aperture / (4.0 * p * kA / kEp), 1.0, 0.05) << r.centre_aperture;
    EXPECT_LT(r.worst_mass_error, 1e-12);
    EXPECT_EQ(r.dissipation, 0.0);
    EXPECT_NEAR(r.pump, r.work + r.dissipation + r.compression, 1e-4 * r.pump);
  }
  // The soft fluid's answer differs visibly from the stiff one, and the run follows it.
  EXPECT_LT(sneddon_pressure(1.0e7) / sneddon_pressure(2.2e9), 0.93);
}

// KGD in the toughness regime (scenes/validation/kgd_toughness.yaml: zero viscosity, K = infinity): the
// fluid breaks the starter crack down and drives it along y = 0. Half-length (the wet network's extent),
// mouth opening and well pressure against the closed form l = 0.9324 (E' Q0 t / K')^(2/3), w0 = 0.6828
// (K'^2 Q0 t / E'^2)^(1/3), p = 0.1831 (K'^4 / (E' Q0 t))^(1/3), at three times after breakdown (0.025 s).
// The crack grows one joint (0.125 m) at a time and the pressure dips after each break, so each is the
// mean of the ratio measured / closed form over the 10 ms before that time. Bound 10 % (the issue's):
// the cohesive zone (l_ch = 4 elements) puts the wet tip ahead of the LEFM tip, the linear tets stiffen
// the crack (Sneddon: w0 +1.2 %), the plate is finite. Measured at 8 elements per metre along the crack's
// path (the graded lattice: 9,000 tets), at 0.05 / 0.075 / 0.1 s: half-length +6.4 / +4.3 / +2.9 %, mouth
// opening +1.8 / +1.6 / +1.8 %, pressure +1.9 / -0.6 / -2.7 % (docs/hydraulic-fracture.md has the
// refinement study).
// Fracture energy: the slope of the solid's fracture dissipation against the area of the joints broken
// since t = 0, over the samples from 0.04 s on, must be G_I within 2 % (the bound). A slope, not a
// ratio of totals: the process zone ahead of the tip holds partly softened joints whose dissipation is
// not yet broken area, a content that moves with the tip but does not grow (16.0 J dissipated against
// 12.5 J of G_I x broken area at 0.1 s). Measured: 93.62 J/m^2 for G_I = 93.75.
struct VertexResult {
  double ratio[3][3] = {};  // per time: half-length, mouth opening, pressure (mean of measured / closed form)
  double worst_mass = 0.0, kinetic = 0.0, work = 0.0, balance = 0.0;
  double energy_per_area = 0.0;  // slope of the fracture dissipation against the area broken, J/m^2
  bool radial = false;           // measured as a quarter penny (CrackGauge), else as a KGD crack
};

// Least-squares slope of y against x.
double slope(const std::vector<std::pair<double, double>>& xy) {
  double mx = 0, my = 0;
  for (const auto& [x, y] : xy) mx += x, my += y;
  mx /= static_cast<double>(xy.size()), my /= static_cast<double>(xy.size());
  double sxy = 0, sxx = 0;
  for (const auto& [x, y] : xy) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx);
  return sxx > 0 ? sxy / sxx : 0.0;
}

// Area of the joints broken since t = 0 (the starter crack's are logged at t = 0).
double area_broken_since_start(Simulation& sim) {
  const Table& events = sim.world().store.table(solid::event_table);
  const auto time = events.span<const double>("time");
  const auto area = events.span<const double>("area");
  double sum = 0.0;
  for (size_t k = 0; k < events.size(); ++k)
    if (time[k] > 0.0) sum += area[k];
  return sum;
}

// A closed form of the KGD crack at time t: half-length, mouth opening and net pressure at the well.
struct ClosedForm {  // NaN where the closed form gives no figure to compare
  double length, opening, net_pressure;
};
using Vertex = std::function<ClosedForm(double t)>;

// The toughness vertex of kgd_toughness.yaml (K' = 4 sqrt(2 / pi) K_Ic, Q0 per unit thickness, whole crack).
ClosedForm toughness_vertex(double t) {
  const double Kp = 4.0 * std::sqrt(2.0 / M_PI) * 1.0e6, Q0 = 8.21e-4 / 0.0625, q = kEp * Q0 * t;
  return {0.9324 * std::pow(q / Kp, 2.0 / 3.0), 0.6828 * std::pow(Kp * Kp * Q0 * t / (kEp * kEp), 1.0 / 3.0),
          0.1831 * std::pow(Kp * Kp * Kp * Kp / q, 1.0 / 3.0)};
}

// The viscosity vertex of kgd_viscous.yaml (mu' = 12 mu; Adachi and Detournay 2002, as GEOS states it).
ClosedForm viscosity_vertex(double t) {
  const double mup = 12.0 * 4.0e-3, Q0 = 6.568e-3 / 0.0625;
  const double w0 = 1.134 * std::pow(mup * Q0 * Q0 * Q0 * t * t / kEp, 1.0 / 6.0);
  return {0.6152 * std::pow(kEp * Q0 * Q0 * Q0 / mup, 1.0 / 6.0) * std::pow(t, 2.0 / 3.0), w0,
          0.62 * std::sqrt(mup * Q0 * kEp) / w0};
}

// Where a case reads its crack: the network point nearest `centre` gives the mouth (KGD) or centre
// (radial) opening; the length is the network's extent from the well (KGD) or the radius of the quarter
// penny of the network's area (radial: the front on a lattice is jagged, its farthest point is not R).
struct CrackGauge {
  std::array<double, 3> centre;
  bool quarter_penny;
};
constexpr CrackGauge kKgdGauge{{0.0, 0.0, 0.0625}, false};
constexpr CrackGauge kRadialGauge{{0.0, 0.0, 0.0}, true};

VertexResult run_against_vertex(const std::string& file, const std::vector<std::string>& overrides,
                                const Vertex& vertex, double confinement = 0.0,
                                const CrackGauge& gauge = kKgdGauge) {
  const double times[3] = {0.05, 0.075, 0.1};
  double sum[3][3] = {}, count[3] = {};
  std::vector<std::pair<double, double>> area_dissipation;  // from the first time on
  VertexResult r;
  r.radial = gauge.quarter_penny;
  const Scene scene = validation_scene(file, overrides);
  run_watching(scene, 2, [&](Simulation& sim) {
    const double t = sim.time();
    int window = -1;
    for (int k = 0; k < 3; ++k)
      if (t > times[k] - 0.01 && t <= times[k] + 1e-12) window = k;
    const bool last = sim.step() == sim.total_steps();
    if (window < 0 && !last && sim.step() % 64 != 0) return;
    std::vector<std::pair<std::string, double>> row;
    flow_of(sim).metrics(t, row);
    const double injected = metric(row, "flow_injected_volume");
    if (injected > 0)
      r.worst_mass = std::max(r.worst_mass, std::abs(metric(row, "flow_mass_error")) / (1000.0 * injected));
    if (t >= times[0] - 0.01) {
      validation::Metrics m(validation::solid_of(sim));
      m.update(t);
      area_dissipation.emplace_back(area_broken_since_start(sim), m["solid_fracture_dissipation"]);
      if (last) {
        r.kinetic = m["solid_kinetic_energy"];
        r.work = m["solid_external_work"];
        r.balance = m["solid_energy_balance_error"];
      }
    }
    if (window < 0) return;
    std::vector<XdmfGrid> grids;
    flow_of(sim).output_grids(grids, {"aperture"});
    const XdmfGrid& g = grids.at(0);
    double best = INFINITY, w0 = 0.0;
    for (size_t p = 0; p < g.point_count; ++p) {
      double d = 0.0;
      for (int c = 0; c < 3; ++c) d += std::abs(g.points[3 * p + size_t(c)] - gauge.centre[size_t(c)]);
      if (d < best) best = d, w0 = static_cast<const double*>(g.fields.at(0).data)[p];
    }
    const ClosedForm exact = vertex(t);
    const double length = gauge.quarter_penny ? std::sqrt(4.0 * metric(row, "flow_crack_area") / M_PI)
                                              : metric(row, "flow_crack_extent");
    sum[window][0] += length / exact.length;
    sum[window][1] += w0 / exact.opening;
    sum[window][2] += (metric(row, "flow_well_pressure") - confinement) / exact.net_pressure;
    count[window] += 1.0;
  });
  for (int k = 0; k < 3; ++k)
    for (int m = 0; m < 3; ++m) r.ratio[k][m] = count[k] > 0 ? sum[k][m] / count[k] : 0.0;
  r.energy_per_area = slope(area_dissipation);
  return r;
}

void expect_vertex(const VertexResult& r, double bound = 0.10) {
  const bool radial = r.radial;
  const char* name = radial ? "Radial" : "KGD";
  const char* names[3] = {radial ? "radius" : "half-length", radial ? "centre opening" : "mouth opening",
                          "net well pressure"};
  const double times[3] = {0.05, 0.075, 0.1};
  for (int k = 0; k < 3; ++k) {
    std::printf("%s at t = %.3f s: %s %+.1f %%, %s %+.1f %%, net pressure %+.1f %%\n", name, times[k],
                names[0], 100.0 * (r.ratio[k][0] - 1.0), names[1], 100.0 * (r.ratio[k][1] - 1.0),
                100.0 * (r.ratio[k][2] - 1.0));
    for (int m = 0; m < 3; ++m)  // NaN: a figure the closed form does not give (ClosedForm)
      if (!std::isnan(r.ratio[k][m]) || m == 0) {
        EXPECT_NEAR(r.ratio[k][m], 1.0, bound) << names[m] << " at t = " << times[k];
      }
  }
  std::printf("%s fracture energy per new crack area %.2f J/m^2 (G_I = %.2f)\n", name, r.energy_per_area,
              kGI);
  // A straight front keeps its length, so its process zone's content is constant and the slope is G_I.
  // A penny's front grows with R: the slope adds (zone content per front length) / R, 113 J/m^2 here.
  if (!radial) {
    EXPECT_NEAR(r.energy_per_area, kGI, 0.02 * kGI);
  }
  EXPECT_LT(r.worst_mass, 1e-12);
  EXPECT_LT(r.kinetic, 0.01 * r.work);            // quasi-static growth
  EXPECT_LT(std::abs(r.balance), 0.02 * r.work);  // the solid's energy balance
}

// The K-vertex of radial_toughness.yaml: Q0 the whole penny's rate (4 x the quarter model's).
ClosedForm radial_toughness_vertex(double t) {
  const double Kp = 4.0 * std::sqrt(2.0 / M_PI) * 1.0e6, Q0 = 4.0 * 8.0e-3, q = kEp * Q0 * t;
  return {0.8546 * std::pow(q / Kp, 0.4), 0.6537 * std::pow(std::pow(Kp / kEp, 4.0) * Q0 * t, 0.2),
          0.3004 * std::pow(std::pow(Kp, 6.0) / q, 0.2)};
}

// The M-vertex radius of radial_viscous.yaml (mu' = 12 mu, Q0 the whole penny's rate). Its opening and
// pressure are not compared: the pressure is log-singular at the well.
ClosedForm radial_viscosity_vertex(double t) {
  const double mup = 12.0 * 4.0e-3, Q0 = 4.0 * 3.18e-2;
  return {0.6976 * std::pow(kEp * Q0 * Q0 * Q0 * std::pow(t, 4.0) / mup, 1.0 / 9.0), NAN, NAN};
}

TEST(HydraulicFracture, KgdToughnessDominatedFollowsTheClosedForm) {
  expect_vertex(run_against_vertex("kgd_toughness.yaml", {}, toughness_vertex));
}

// The same with a viscous fluid, mu = 1e-6 Pa s: K = K' / (E'^3 mu' Q0)^(1/4) = 4.8, still in the
// toughness regime (K >~ 4), now with a flow solve every step, lag and cavitation at the tip, and closing
// vertices (the closure's active set). Measured at 0.05 / 0.075 / 0.1 s: half-length +6.2 / +4.2 / +2.4 %,
// mouth opening +2.5 / +2.2 / +2.4 %, pressure +3.8 / +1.1 / -0.9 %; fracture energy 94.00 J/m^2.
TEST(HydraulicFracture, KgdWithAViscousFluidInTheToughnessRegime) {
  expect_vertex(run_against_vertex("kgd_toughness.yaml", {"fracture_flow.viscosity=1e-6"}, toughness_vertex));
}

// KGD in the viscosity regime (scenes/validation/kgd_viscous.yaml: mu = 4 mPa s, K = 0.36, 3 MPa across
// the crack plane, which closes the fluid lag the M-vertex assumes away): half-length, mouth opening and
// net well pressure against the M-vertex at 0.05 / 0.075 / 0.1 s. Bound 15 % (the for this
// regime): the starter crack (1 m, a third of the final length) is a memory the self-similar solution
// does not have, the measured extent counts the wet process zone, and the mesh is the toughness case's.
// Measured: half-length +13.4 / +10.8 / +9.6 %, mouth opening -3.7 / -3.3 / -3.0 %, net pressure -6.3 /
// -8.6 / -11.4 % (the length's error falls as the starter's memory fades; the pressure's grows).
TEST(HydraulicFracture, KgdViscosityDominatedFollowsTheMVertex) {
  expect_vertex(run_against_vertex("kgd_viscous.yaml", {}, viscosity_vertex, 3.0e6), 0.15);
}

// The same crack held at 1 MPa by a pressure-controlled well: it takes in Sneddon's volume
// V = 2 pi p a^2 / E' (within the prescribed-pressure test's 5 %), and the well's pressure is the one given.
TEST(HydraulicFracture, APressureControlledWellFillsSneddonsVolume) {
  const Scene scene = validation_scene("sneddon_injection.yaml",
                                       {"fracture_flow.injection={point: [0, 0, 0.0625], pressure: 1.0e6}"});
  std::vector<std::pair<std::string, double>> row;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (sim.step() != sim.total_steps()) return;
    flow_of(sim).metrics(sim.time(), row);
  });
  EXPECT_EQ(metric(row, "flow_well_pressure"), 1.0e6);
  const double volume = metric(row, "flow_crack_volume") * 16.0;  // both halves, per metre of crack
  EXPECT_NEAR(volume / (2.0 * M_PI * 1.0e6 * kA * kA / kEp), 1.0, 0.05);
  // The well gave what the crack holds, but for the fluid that filled the starter crack's floor aperture
  // at t = 0 (1e-8 m over 0.125 m^2).
  EXPECT_NEAR(metric(row, "flow_fluid_volume") - metric(row, "flow_injected_volume"), 1.25e-9, 1e-12);
}

// Carter leak-off from a crack wet since t = 0: each face loses C_L / sqrt(t) per unit area, so between t1
// and t2 the crack of face area A loses 2 A 2 C_L (sqrt(t2) - sqrt(t1)). Measured from t1 = 5 ms, once the
// injection has filled the crack (before, a vertex cannot lose more than it holds). The step integrates
// C_L / sqrt(t) exactly; the leaked mass is counted at rho(p) and reported at rho0 (p / K_f < 5e-4).
TEST(HydraulicFracture, LeakOffFollowsCarter) {
  const double cl = 1.0e-4;
  const Scene scene = validation_scene(
      "sneddon_injection.yaml",
      {"mesh.generate.graded.size=0.25", "solid.fracture.box_min=[-1, -0.225, -1]",
       "solid.fracture.box_max=[1.25, 0.225, 1]", "fracture_flow.leak_off=" + std::to_string(cl)});
  double t1 = -1.0, leaked1 = 0.0, worst = 0.0;
  size_t samples = 0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (sim.time() < 0.005 || sim.step() % 250 != 0) return;
    std::vector<std::pair<std::string, double>> row;
    flow_of(sim).metrics(sim.time(), row);
    const double leaked = metric(row, "flow_leaked_volume"), area = metric(row, "flow_crack_area");
    if (t1 < 0) {
      t1 = sim.time(), leaked1 = leaked;
      return;
    }
    const double carter = 2.0 * area * 2.0 * cl * (std::sqrt(sim.time()) - std::sqrt(t1));
    worst = std::max(worst, std::abs((leaked - leaked1) / carter - 1.0));
    ++samples;
  });
  EXPECT_GT(samples, 10u);
  EXPECT_LT(worst, 1e-3);
}

// The example a new user runs (scenes/examples/hydraulic_fracture.yaml), for its first 2 ms: the well's
// pressure rises to breakdown (above the 1 MPa the least stress holds the crack shut with) and falls
// while the crack grows past its starter radius (0.025 m, 0.028 m to the farthest vertex).
TEST(HydraulicFracture, TheExampleBreaksDownAndGrows) {
  const Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/examples/hydraulic_fracture.yaml",
                                 {"time.end=2.0e-3"});
  double peak = 0.0, last = 0.0, extent = 0.0;
  run_watching(scene, 2, [&](Simulation& sim) {
    if (sim.step() % 100 != 0 && sim.step() != sim.total_steps()) return;
    std::vector<std::pair<std::string, double>> row;
    flow_of(sim).metrics(sim.time(), row);
    last = metric(row, "flow_well_pressure");
    peak = std::max(peak, last);
    extent = metric(row, "flow_crack_extent");
  });
  EXPECT_GT(peak, 5.0e6);
  EXPECT_LT(last, 0.9 * peak);
  EXPECT_GT(extent, 0.035);
}

// A viscous fluid in the same crack, on a coarser mesh and a shorter run: the same bits on 1, 2 and 4
// threads, and a run stopped half-way and restarted from its checkpoint ends on the same bits.
TEST(HydraulicFracture, ViscousInjectionIsDeterministicAndRestartsBitForBit) {
  const Scene scene = validation_scene(
      "sneddon_injection.yaml", {"mesh.generate.graded.size=0.25", "solid.fracture.box_min=[-1, -0.225, -1]",
                                 "solid.fracture.box_max=[1.25, 0.225, 1]", "fracture_flow.viscosity=1e-3",
                                 "time.end=0.004", "checkpoint.every_steps=200", "output.interval=0.001"});
  validation::expect_same_bits_on_threads_and_restart(scene, 400);
}

// The radial scenes on 1/6 m cells (theirs are 1/8 m, which the benchmarks use): a third of the run time,
// within the bounds (the refinement study in docs/hydraulic-fracture.md gives both meshes and 1/10 m).
const std::vector<std::string> kRadialCoarse{"mesh.generate.graded.size=0.1666666666666667",
                                             "mesh.generate.graded.fine_min=[0, 0, -0.3333333333333333]",
                                             "mesh.generate.graded.fine_max=[3.0, 3.0, 0.3333333333333333]",
                                             "solid.fracture.box_min=[-1, -1, -0.15]",
                                             "solid.fracture.box_max=[3.0, 3.0, 0.15]"};

// Radial (penny) fracture in the toughness regime (scenes/validation/radial_toughness.yaml: zero
// viscosity, K_m = infinity, quarter model on a graded lattice): radius (of the quarter penny with the
// network's area), centre opening and well pressure against the K-vertex R = 0.8546 (E' Q0 t / K')^(2/5),
// w0 = 0.6537 (K'^4 Q0 t / E'^4)^(1/5), p = 0.3004 (K'^6 / (E' Q0 t))^(1/5) at 0.05 / 0.075 / 0.1 s, as
// the KGD case: the mean of measured / closed form over the 10 ms before each time, bound 10 % (the
// issue's), for the same reasons (cohesive zone of l_ch = 3 cells, linear tets, finite block: 2.7 final
// radii to the faces). Measured on 1/6 m cells: radius +7.9 / +6.6 / +5.2 %, centre opening +2.1 / +2.1 /
// +2.7 %, net pressure +0.2 / -1.0 / -1.4 %. The fracture energy is checked on KGD only: a penny's front
// lengthens as it grows, and the process zone along it with it (the dissipation's slope against the broken
// area is 113 J/m^2 for G_I = 93.75 on 1/8 m cells, 115 on 1/6; fits with a term per front length give 87 -
// 98 J/m^2 depending on the model of the zone, too uncertain for a bound).
TEST(HydraulicFracture, RadialToughnessDominatedFollowsTheKVertex) {
  expect_vertex(
      run_against_vertex("radial_toughness.yaml", kRadialCoarse, radial_toughness_vertex, 0.0, kRadialGauge),
      0.10);
}

// Radial fracture in the viscosity regime (scenes/validation/radial_viscous.yaml: mu = 4 mPa s, K_m = 0.46
// at 0.1 s, 3 MPa across the crack plane to close the dry lag as in kgd_viscous.yaml): the radius against
// the M-vertex R = 0.6976 (E' Q0^3 t^4 / mu')^(1/9) at 0.05 / 0.075 / 0.1 s, bound 15 % (the for
// this regime: the starter penny is a memory the self-similar solution lacks, the measured radius counts
// the wet process zone). Measured on 1/6 m cells: +12.2 / +10.1 / +8.7 %.
TEST(HydraulicFracture, RadialViscosityDominatedFollowsTheMVertex) {
  expect_vertex(
      run_against_vertex("radial_viscous.yaml", kRadialCoarse, radial_viscosity_vertex, 3.0e6, kRadialGauge),
      0.15);
}

// Venting (scenes/validation/vent_slot.yaml): a crack driven from a 1 m starter to the open face of a 2 m
// slab, which vents to 0 Pa once the fluid reaches it. Checked: the mass books every step to 1e-12 of the
// injected mass; not a drop vented or drawn in while the fluid front is more than a cell (0.125 m) from
// the face (the vent vertices join the network when their joints break, dry, ahead of the fluid: a vent
// that held its pressure from then on drew 2e-6 m^3 in from outside); every network point on the face
// at the vent pressure at the end; and over the last 10 ms the vented rate within 2 % of the injected
// one (measured -0.33 %: the crack still stores what its slowly rising pressure asks).
TEST(HydraulicFracture, ACrackVentsWhereTheFluidReachesAnOpenFace) {
  const Scene scene = validation_scene("vent_slot.yaml");
  const double rate = 1.0e-2, end = scene.time.end;
  double worst_mass = 0.0, vented_before_arrival = 0.0, vented_at = 0.0, vented_end = 0.0;
  bool arrived = false;
  size_t face_points = 0;
  run_watching(scene, 2, [&](Simulation& sim) {
    std::vector<std::pair<std::string, double>> row;
    flow_of(sim).metrics(sim.time(), row);
    const double injected = metric(row, "flow_injected_volume"), vented = metric(row, "flow_vented_volume");
    if (injected > 0)
      worst_mass = std::max(worst_mass, std::abs(metric(row, "flow_mass_error")) / (1000.0 * injected));
    arrived = arrived || metric(row, "flow_front_extent") > 2.0 - 0.125 - 1e-9;
    if (!arrived) vented_before_arrival = std::max(vented_before_arrival, std::abs(vented));
    if (sim.time() <= end - 0.01 + 1e-12) vented_at = vented;
    if (sim.step() != sim.total_steps()) return;
    vented_end = vented;
    std::vector<XdmfGrid> grids;
    flow_of(sim).output_grids(grids, {"pressure"});
    const XdmfGrid& g = grids.at(0);
    for (size_t p = 0; p < g.point_count; ++p)
      if (std::abs(g.points[3 * p] - 2.0) < 1e-3) {  // on the face, as deformed (microns)
        ++face_points;
        EXPECT_EQ(static_cast<const double*>(g.fields.at(0).data)[p], 0.0) << "network point " << p;
      }
  });
  EXPECT_TRUE(arrived);
  EXPECT_EQ(vented_before_arrival, 0.0);
  EXPECT_GT(face_points, 0u);
  EXPECT_LT(worst_mass, 1e-12);
  const double vented_rate = (vented_end - vented_at) / 0.01;
  std::printf("vented %.6g m^3/s over the last 10 ms for %.6g injected\n", vented_rate, rate);
  EXPECT_NEAR(vented_rate, rate, 0.02 * rate);
}

}  // namespace
}  // namespace rift
