// The paper's observations (Guo et al. 2015, section 5) on the coupled wedge's coarse preset
// (scenes/examples/guo2015_wedge.yaml: 4 / 8 mm tets, 4 mm fluid cells at the notch, mass scaling 1.5e-8 s),
// the part of them that holds up to 0.2 ms (0.1 ms into the ramp):
//  - no joint breaks while the inlet holds 15 MPa (0.1 ms), nor while it holds 14 MPa for as long;
//  - the crack starts after the ramp begins, at the notch's tip (its first break within two elements,
//    16 mm, of the tip's line x = 24.5 mm, y = 50 mm), and runs close to the notch's plane (the broken
//    joints' RMS distance from y = 50 mm below two elements);
//  - every 25 us from 0.1 ms: tension concentrates ahead of the crack's tip (the tet of the largest
//    sigma_yy within two elements of the tip's line: the notch's tip, or the broken joint farthest along
//    x within 5 mm of the notch's plane); once the crack exists, the network's fluid trails its tip (the
//    wetted network point farthest along x short of the network's farthest point: a lag), fluid is in the
//    crack (the fluid cell that holds each broken joint's centroid has a solid fraction below 1) and the
//    fluid's mesh is refined along it (the median edge of those cells below the mesh's median);
//  - after every fluid step, the surrounding fluid (the nodes of the cells with a solid fraction below
//    0.5 that the cracks' network does not own) holds the inlet's P(t) within the 0.5 MPa.
// Tolerances in elements: a crack can only follow the tets' faces, so its path, its first break and the
// stress peak are known to the element's size (the largest, 8 mm) and no closer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/table.hpp"
#include "systems/coupling/fluid_solid_model.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/solid_tables.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"
#include "tests/validation/fracture_flow_support.hpp"
#include "tests/validation/paper_wedge_support.hpp"
#include "tests/validation/validation_support.hpp"

namespace rift {
namespace {

constexpr double kElement = 0.008;                     // the coarse preset's largest tet
constexpr double kTipX = 0.0245, kNotchPlaneY = 0.05;  // the notch's tip line (through z)
constexpr double kRampStart = 1.0e-4;

// No field outputs: the breaks are read from fractures.csv.
Scene coarse_wedge(std::vector<std::string> more) {
  more.push_back("output.interval=1.0e-3");
  return validation::coupled_wedge_coarse(more);
}

struct Break {
  double time, x, y, z;
};

// fractures.csv: step,time,joint,tet_a,tet_b,mode,x,y,z,...
std::vector<Break> breaks_of(const std::filesystem::path& run) {
  std::ifstream in(run / "fractures.csv");
  std::string line;
  std::getline(in, line);
  std::vector<Break> out;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::vector<std::string> cell;
    for (std::string c; std::getline(s, c, ',');) cell.push_back(c);
    out.push_back({std::stod(cell[1]), std::stod(cell[6]), std::stod(cell[7]), std::stod(cell[8])});
  }
  return out;
}

TEST(PaperWedgeObservations, NoBreakAt14MPaHeldForTheSettlingsTime) {
  test::TempDir dir;
  std::vector<std::string> at14{"time.end=1.0e-4", "fluid.initial_pressure=1.4e7"};
  for (int face = 0; face < 6; ++face)  // the fluid's box holds P(t) on every face
    at14.push_back("fluid.boundaries[" + std::to_string(face) + "].value.ramp.value=1.4e7");
  const Scene scene = coarse_wedge(at14);
  ASSERT_TRUE(test::run_scene(scene, dir / "run", 2).completed);
  EXPECT_TRUE(breaks_of(dir / "run").empty());
}

// The solid's fracture log (solid_fracture_event): every break so far.
std::vector<Break> breaks_of(const Store& store) {
  const Table& events = store.table(solid::event_table);
  const auto time = events.span<const double>("time");
  const auto centroid = events.span<const double>("centroid");
  std::vector<Break> out;
  for (size_t e = 0; e < events.size(); ++e)
    out.push_back({time[e], centroid[3 * e], centroid[3 * e + 1], centroid[3 * e + 2]});
  return out;
}

// The crack's tip along x: the notch's tip, or the broken joint farthest along x near the notch's plane.
double tip_x(const std::vector<Break>& breaks) {
  double x = kTipX;
  for (const Break& b : breaks)
    if (std::abs(b.y - kNotchPlaneY) < 0.005) x = std::max(x, b.x);
  return x;
}

// The fluid cell that holds point q (barycentric coordinates), or -1.
int64_t cell_holding(std::span<const double> x, std::span<const int32_t> tets, const double q[3]) {
  for (size_t k = 0; 4 * k < tets.size(); ++k) {
    const double* p[4];
    for (size_t a = 0; a < 4; ++a) p[a] = &x[3 * size_t(tets[4 * k + a])];
    double m[3][3], r[3];
    for (int d = 0; d < 3; ++d) {
      for (int c = 0; c < 3; ++c) m[d][c] = p[c + 1][d] - p[0][d];
      r[d] = q[d] - p[0][d];
    }
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    double lam[3];
    for (int c = 0; c < 3; ++c) {  // Cramer's rule
      double mc[3][3];
      for (int d = 0; d < 3; ++d)
        for (int e = 0; e < 3; ++e) mc[d][e] = e == c ? r[d] : m[d][e];
      lam[c] = (mc[0][0] * (mc[1][1] * mc[2][2] - mc[1][2] * mc[2][1]) -
                mc[0][1] * (mc[1][0] * mc[2][2] - mc[1][2] * mc[2][0]) +
                mc[0][2] * (mc[1][0] * mc[2][1] - mc[1][1] * mc[2][0])) /
               det;
    }
    const double eps = 1e-9;
    if (lam[0] >= -eps && lam[1] >= -eps && lam[2] >= -eps && lam[0] + lam[1] + lam[2] <= 1 + eps)
      return int64_t(k);
  }
  return -1;
}

// The surrounding fluid's pressure range less the inlet's P(t), from the coupling's time-series columns.
std::pair<double, double> region_pressure_deviation(Simulation& sim, const TimeFunction& inlet) {
  std::vector<std::pair<std::string, double>> row;
  for (auto& m : sim.world().models)
    if (auto* c = dynamic_cast<FluidSolidModel*>(m.get())) c->metrics(sim.time(), row);
  double lo = 0.0, hi = 0.0;
  for (const auto& [name, value] : row) {
    if (name == "fluid_region_pressure_min") lo = value - inlet(sim.time());
    if (name == "fluid_region_pressure_max") hi = value - inlet(sim.time());
  }
  return {lo, hi};
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(PaperWedgeObservations, TheCrackStartsAtTheTipTensionLeadsItTheFluidTrailsItAndTheMeshFollows) {
  const Scene scene = coarse_wedge({"time.end=2.0e-4"});
  const double every = 2.5e-5;
  const TimeFunction& inlet = scene.fluid->boundaries.at(0).function;  // the inlet's P(t)
  double next = kRampStart, next_fluid = scene.fluid->dt;
  int checks = 0, crack_checks = 0;
  double region_low = 0.0, region_high = 0.0;
  std::vector<Break> breaks;
  const RunResult r = validation::run_watching(scene, 2, [&](Simulation& sim) {
    if (sim.time() >= next_fluid - 1e-3 * sim.dt()) {  // the fluid has just stepped to this time
      next_fluid += scene.fluid->dt;
      const auto [lo, hi] = region_pressure_deviation(sim, inlet);
      region_low = std::min(region_low, lo);
      region_high = std::max(region_high, hi);
    }
    if (sim.time() < next - 1e-3 * sim.dt()) return;
    next += every;
    ++checks;
    const Store& store = sim.world().store;
    breaks = breaks_of(store);
    const double tip = tip_x(breaks);
    // The tet of the largest sigma_yy, against the tip's line.
    const auto stress = store.table(solid::tet_table).span<const double>("stress");
    const auto nodes = store.table(solid::tet_table).span<const int32_t>("nodes");
    const auto xs = store.table(solid::node_table).span<const double>("x");
    size_t peak = 0;
    for (size_t t = 1; 6 * t < stress.size(); ++t)
      if (stress[6 * t + 1] > stress[6 * peak + 1]) peak = t;
    double c[3] = {0, 0, 0};
    for (size_t a = 0; a < 4; ++a)
      for (size_t d = 0; d < 3; ++d) c[d] += 0.25 * xs[3 * size_t(nodes[4 * peak + a]) + d];
    const double off = std::hypot(c[0] - tip, c[1] - kNotchPlaneY);
    std::printf("%.4g ms: tip x %.1f mm, sigma_yy peak %.2f MPa %.1f mm from it", sim.time() * 1e3, tip * 1e3,
                stress[6 * peak + 1] * 1e-6, off * 1e3);
    EXPECT_LT(off, 2 * kElement) << "at " << sim.time();
    if (breaks.empty()) {
      std::printf("\n");
      return;
    }
    ++crack_checks;
    // The network's fluid front (its wetted point farthest along x) and its reach (its farthest point: the
    // broken joints and the process zone's, which the network takes in once they soften).
    std::vector<XdmfGrid> grids;
    validation::flow_of(sim).output_grids(grids, {"wetting_time"});
    const XdmfGrid& net = grids.at(0);
    const auto* wetting = static_cast<const double*>(net.fields.at(0).data);
    double front = 0.0, reach = 0.0;
    for (size_t p = 0; p < net.point_count; ++p) {
      reach = std::max(reach, net.points[3 * p]);
      if (wetting[p] >= 0.0) front = std::max(front, net.points[3 * p]);
    }
    // The fluid cells holding the broken joints' centroids: their solid fraction and size.
    fluid::FluidSolver& solver = [&]() -> fluid::FluidSolver& {
      for (auto& m : sim.world().models)
        if (auto* f = dynamic_cast<FluidModel*>(m.get())) return f->solver();
      throw std::runtime_error("no fluid");
    }();
    const auto alpha = store.table(fluid::tet_table).span<const double>("solid_fraction");
    const auto volume = solver.volumes();
    std::vector<double> edge(volume.size()), crack_edge;
    for (size_t k = 0; k < volume.size(); ++k) edge[k] = std::cbrt(6 * std::sqrt(2.0) * volume[k]);
    double worst_alpha = 0.0;
    size_t outside = 0;
    for (const Break& b : breaks) {
      const double q[3] = {b.x, b.y, b.z};
      const int64_t k = cell_holding(solver.nodes(), solver.tets(), q);
      if (k < 0) {
        ++outside;
        continue;
      }
      worst_alpha = std::max(worst_alpha, alpha[size_t(k)]);
      crack_edge.push_back(edge[size_t(k)]);
    }
    std::printf(
        "; %zu broken, network to x %.1f mm, its fluid front x %.1f mm; crack cells: alpha up to %.6f, "
        "median edge %.1f mm (mesh "
        "%.1f)\n",
        breaks.size(), reach * 1e3, front * 1e3, worst_alpha, median(crack_edge) * 1e3, median(edge) * 1e3);
    EXPECT_LT(front, reach) << "at " << sim.time();
    EXPECT_EQ(outside, 0u);
    EXPECT_LT(worst_alpha, 1.0) << "at " << sim.time();
    EXPECT_LT(median(crack_edge), median(edge)) << "at " << sim.time();
  });
  ASSERT_TRUE(r.completed);
  EXPECT_EQ(checks, 5);
  EXPECT_GE(crack_checks, 2);
  ASSERT_FALSE(breaks.empty()) << "no break by 0.2 ms (0.1 ms into the ramp)";
  const Break& first = breaks.front();
  double sq = 0.0;
  for (const Break& b : breaks) sq += (b.y - kNotchPlaneY) * (b.y - kNotchPlaneY);
  const double rms = std::sqrt(sq / double(breaks.size()));
  std::printf(
      "first break at %.4g ms, (%.4g, %.4g, %.4g) mm; %zu broken by 0.2 ms, RMS off the plane %.3g mm\n",
      first.time * 1e3, first.x * 1e3, first.y * 1e3, first.z * 1e3, breaks.size(), rms * 1e3);
  EXPECT_GT(first.time, kRampStart);  // none while the inlet holds 15 MPa
  EXPECT_LT(std::hypot(first.x - kTipX, first.y - kNotchPlaneY), 2 * kElement);
  EXPECT_LT(rms, 2 * kElement);
  std::printf("the surrounding fluid less P(t), every fluid step to 0.2 ms: %.3f / %+.3f MPa\n",
              region_low * 1e-6, region_high * 1e-6);
  EXPECT_GT(region_low, -0.5e6);
  EXPECT_LT(region_high, 0.5e6);
}

}  // namespace
}  // namespace rift
