// Lubrication flow on a crack network (systems/fracture_flow/network_flow.hpp): the equation of state
// inverted exactly, the cubic law through a slot on structured and distorted meshes, the zero-viscosity
// mode's single pressure, and mass conservation while a front advances into a dry crack.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "kernels/fracture_flow.hpp"
#include "systems/fracture_flow/network_flow.hpp"

namespace rift {
namespace {

const kernels::FluidEos kWater{1000.0, 0.0, 2.2e9};

TEST(FractureFlowEos, PressureOfMassInvertsTheEquationOfState) {
  // Without compliance: p = p0 + K_f (m / (rho0 V) - 1), exactly the equation of state.
  EXPECT_NEAR(kernels::pressure_of_mass(kWater, 1001.0, 1.0, 0.0, 0.0), 2.2e6, 1e-6);
  // With compliance, across six decades of pressure and both signs of the reference: rho(p) V(p) = m.
  for (double p_true : {-1e5, 1e3, 1e5, 3e6, 5e7, 4e8})
    for (double c : {0.0, 1e-15, 1e-12, 1e-9})
      for (double p_ref : {0.0, 1e6}) {
        const double v0 = 2e-6;
        const double m = kWater.density(p_true) * (v0 + c * (p_true - p_ref));
        const double p = kernels::pressure_of_mass(kWater, m, v0, c, p_ref);
        EXPECT_NEAR(p, p_true, 1e-9 * std::max(1e6, std::abs(p_true))) << p_true << " " << c << " " << p_ref;
      }
}

TEST(FractureFlowKernels, CrackTriangleOpeningFollowsTheJointConvention) {
  // Side A above side B by 1e-4 along z; corners 0-2 reversed (A's outward normal is -z) so n = +z.
  const double a0[3] = {0, 0, 1e-4}, a1[3] = {0, 1, 1e-4}, a2[3] = {1, 0, 1e-4};
  const double b0[3] = {0, 0, 0}, b1[3] = {0, 1, 0}, b2[3] = {1, 0, 0};
  const double* corners[6] = {a0, a1, a2, b0, b1, b2};
  const kernels::CrackTriangle t = kernels::crack_triangle(corners);
  EXPECT_DOUBLE_EQ(t.area, 0.5);
  EXPECT_DOUBLE_EQ(t.normal[2], -1.0);                    // (m1 - m0) x (m2 - m0) = (0,1,0) x (1,0,0) = -z
  for (double o : t.opening) EXPECT_DOUBLE_EQ(o, -1e-4);  // A above B along -n: interpenetration
}

// A rectangular strip [0, L] x [0, W] of nx x ny cells, each cut into two triangles; interior vertices
// moved by up to `jitter` of a cell (the P1 solution of a linear field does not depend on the mesh).
struct Strip {
  std::vector<double> vx;  // 3 per vertex
  std::vector<int32_t> tri;
  int nx, ny;
  size_t vertex(int i, int j) const { return size_t(j * (nx + 1) + i); }
};

Strip make_strip(double L, double W, int nx, int ny, double jitter, unsigned seed) {
  Strip s{{}, {}, nx, ny};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const bool inner = i > 0 && i < nx && j > 0 && j < ny;
      s.vx.insert(s.vx.end(),
                  {(i + (inner ? u(rng) : 0.0)) * L / nx, (j + (inner ? u(rng) : 0.0)) * W / ny, 0.0});
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int32_t a = int32_t(s.vertex(i, j)), b = int32_t(s.vertex(i + 1, j)),
                    c = int32_t(s.vertex(i + 1, j + 1)), d = int32_t(s.vertex(i, j + 1));
      if ((i + j) % 2)
        s.tri.insert(s.tri.end(), {a, b, c, a, c, d});
      else
        s.tri.insert(s.tri.end(), {a, b, d, b, c, d});
    }
  return s;
}

// Per-step inputs of a rigid network: apertures w everywhere, volumes the lumped A w / 3.
struct RigidNetwork {
  std::vector<double> tx, aperture, volume, compliance, applied, source, fixed;
  RigidNetwork(const std::vector<double>& vx, const std::vector<int32_t>& tri, double w) {
    const size_t nv = vx.size() / 3;
    volume.assign(nv, 0.0);
    for (size_t t = 0; t < tri.size() / 3; ++t) {
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) tx.push_back(vx[3 * size_t(tri[3 * t + size_t(c)]) + size_t(d)]);
      double k[3];
      const double area = kernels::p1_edge_coefficients(&tx[9 * t], &tx[9 * t + 3], &tx[9 * t + 6], k);
      for (int c = 0; c < 3; ++c) {
        aperture.push_back(w);
        volume[size_t(tri[3 * t + size_t(c)])] += area * w / 3.0;
      }
    }
    compliance.assign(nv, 0.0);
    applied.assign(nv, 0.0);
    source.assign(nv, 0.0);
    fixed.assign(nv, 0.0);
  }
  NetworkFlowStepInput input(double dt, double time) const {
    return {dt, time, tx, aperture, volume, compliance, applied, source, fixed};
  }
};

struct VertexState {
  std::vector<double> pressure, mass, wetting, exchanged;
  std::vector<uint8_t> role;
  explicit VertexState(size_t n)
      : pressure(n, 0.0), mass(n, 0.0), wetting(n, -1.0), exchanged(n, 0.0), role(n, 0) {}
  NetworkFlowState view() { return {pressure, mass, role, wetting, exchanged}; }
  double total_mass() const { return std::accumulate(mass.begin(), mass.end(), 0.0); }
  double total_exchanged() const { return std::accumulate(exchanged.begin(), exchanged.end(), 0.0); }
};

// The cubic law: a slot of aperture w between pressures p1 and p2 carries q = w^3 (p1 - p2) W / (12 mu L)
// in steady state, on any triangulation (P1 reproduces a linear pressure exactly). A stiff fluid (K_f =
// 1e20 Pa) makes the density uniform, so the mass flux is rho0 q; 1e-10 is rounding over 1e3 edges.
TEST(NetworkFlow, SlotCarriesTheCubicLawFlux) {
  const double L = 0.1, W = 0.02, w = 1e-4, mu = 1e-3, p1 = 2e6, p2 = 5e5;
  const kernels::FluidEos stiff{1000.0, 0.0, 1e20};
  for (double jitter : {0.0, 0.3})
    for (int nx : {10, 37}) {
      const Strip s = make_strip(L, W, nx, 5, jitter, 7);
      RigidNetwork net(s.vx, s.tri, w);
      const size_t nv = s.vx.size() / 3;
      VertexState st(nv);
      for (int j = 0; j <= s.ny; ++j) {
        for (auto [i, p] : {std::pair{0, p1}, std::pair{s.nx, p2}}) {
          st.role[s.vertex(i, j)] = uint8_t(FlowRole::fixed);
          net.fixed[s.vertex(i, j)] = p;
        }
      }
      for (size_t v = 0; v < nv; ++v)
        if (st.role[v] != uint8_t(FlowRole::fixed)) {
          st.role[v] = uint8_t(FlowRole::wet);
          st.mass[v] = stiff.density(p2) * net.volume[v];
          st.pressure[v] = p2;
        }
      NetworkFlow flow(stiff, mu, 0.0);
      flow.set_network(s.tri, nv);
      NetworkFlowBooks books;
      const double dt = 1.0;  // far beyond the slot's diffusion time: steady after a step or two
      for (int k = 0; k < 3; ++k) {
        std::fill(st.exchanged.begin(), st.exchanged.end(), 0.0);
        auto view = st.view();
        ASSERT_EQ(flow.step(net.input(dt, dt * (k + 1)), view, books), "");
      }
      double in = 0.0, out = 0.0;
      for (int j = 0; j <= s.ny; ++j) {
        in += st.exchanged[s.vertex(0, j)];
        out -= st.exchanged[s.vertex(s.nx, j)];
      }
      const double q = w * w * w * (p1 - p2) * W / (12.0 * mu * L);
      EXPECT_NEAR(in / (dt * stiff.density0), q, 1e-10 * q) << "nx " << nx << " jitter " << jitter;
      EXPECT_NEAR(out / (dt * stiff.density0), q, 1e-10 * q) << "nx " << nx << " jitter " << jitter;
      for (size_t v = 0; v < nv; ++v) {  // the linear profile
        const double x = s.vx[3 * v];
        EXPECT_NEAR(st.pressure[v], p1 + (p2 - p1) * x / L, 1e-9 * p1);
      }
    }
}

// A borehole's well gathers every crack point on its wall into one vertex, so triangles at the wall have
// two corners on it. With the slot's inlet edge gathered into one well vertex held at p1, the flux is the
// cubic law's all the same (the gathered points have one pressure in the exact solution too): 1e-10 as
// above.
TEST(NetworkFlow, AWellGatheringTheInletEdgeCarriesTheCubicLawFlux) {
  const double L = 0.1, W = 0.02, w = 1e-4, mu = 1e-3, p1 = 2e6, p2 = 5e5;
  const kernels::FluidEos stiff{1000.0, 0.0, 1e20};
  const Strip s = make_strip(L, W, 12, 5, 0.3, 11);
  const RigidNetwork geometry(s.vx, s.tri, w);  // corner positions and apertures of the real triangles
  // Vertex 0 is the well; the others keep their order.
  std::vector<int32_t> id(s.vx.size() / 3, -1);
  int32_t next = 1;
  for (size_t v = 0; v < id.size(); ++v) id[v] = s.vx[3 * v] == 0.0 ? 0 : next++;
  std::vector<int32_t> merged;
  for (int32_t v : s.tri) merged.push_back(id[size_t(v)]);
  const size_t nv = size_t(next);
  RigidNetwork net = geometry;
  net.volume.assign(nv, 0.0);
  for (size_t v = 0; v < id.size(); ++v) net.volume[size_t(id[v])] += geometry.volume[v];
  for (auto* a : {&net.compliance, &net.applied, &net.source, &net.fixed}) a->assign(nv, 0.0);
  VertexState st(nv);
  for (size_t v = 0; v < id.size(); ++v) {
    const size_t m = size_t(id[v]);
    const bool outlet = std::abs(s.vx[3 * v] - L) < 1e-12 * L;
    st.role[m] = uint8_t(m == 0 || outlet ? FlowRole::fixed : FlowRole::wet);
    net.fixed[m] = m == 0 ? p1 : p2;
    st.pressure[m] = m == 0 ? p1 : p2;
  }
  for (size_t m = 0; m < nv; ++m) st.mass[m] = stiff.density(st.pressure[m]) * net.volume[m];
  NetworkFlow flow(stiff, mu, 0.0);
  flow.set_network(merged, nv);
  NetworkFlowBooks books;
  for (int k = 0; k < 3; ++k) {
    std::fill(st.exchanged.begin(), st.exchanged.end(), 0.0);
    auto view = st.view();
    ASSERT_EQ(flow.step(net.input(1.0, k + 1.0), view, books), "");
  }
  const double q = w * w * w * (p1 - p2) * W / (12.0 * mu * L);
  EXPECT_NEAR(st.exchanged[0] / stiff.density0, q, 1e-10 * q);
  for (size_t v = 0; v < id.size(); ++v)
    EXPECT_NEAR(st.pressure[size_t(id[v])], p1 + (p2 - p1) * s.vx[3 * v] / L, 1e-9 * p1);
}

// A crack drained fast through a vent while its walls, much more compliant than its fluid, close within the
// step: the linearised volume V_pred + C (p - p_applied) of a wet vertex would fall below its floor, even
// with only its open corners' compliance, and its mass below zero (the run stopped, "drew more fluid out
// of vertex ... than it held"). Such a vertex closes onto its floor and no further: its volume is the floor
// volume, every mass stays positive, the books close, and its walls take the pressure change that brings
// its open corners to the floor (V_pred + C_open (p_wall - p_applied) = V_floor), not the whole drop.
TEST(NetworkFlow, AVertexClosingPastItsFloorStopsAtItsFloor) {
  const Strip s = make_strip(0.02, 0.004, 10, 2, 0.2, 5);
  RigidNetwork net(s.vx, s.tri, 2e-5);
  const size_t nv = s.vx.size() / 3;
  const double p0 = 3e6;
  std::vector<double> floor(nv), open(nv);
  VertexState st(nv);
  for (size_t v = 0; v < nv; ++v) {
    net.compliance[v] = 10.0 * net.volume[v] / 1e6;  // a 1 MPa drop would close ten volumes
    open[v] = net.compliance[v];                     // every corner open
    floor[v] = 0.5 * net.volume[v];
    net.applied[v] = p0;
    st.role[v] = uint8_t(FlowRole::wet);
    st.pressure[v] = p0;
    st.mass[v] = kWater.density(p0) * net.volume[v];
  }
  for (int j = 0; j <= s.ny; ++j) {
    st.role[s.vertex(0, j)] = uint8_t(FlowRole::fixed);
    net.fixed[s.vertex(0, j)] = 0.0;
  }
  NetworkFlow flow(kWater, 1e-3, -1e5);
  flow.set_network(s.tri, nv);
  NetworkFlowBooks books;
  const double m0 = st.total_mass();
  auto view = st.view();
  const NetworkFlowStepInput in{1e-2,        1e-2,       net.tx,    net.aperture, net.volume, net.compliance,
                                net.applied, net.source, net.fixed, open,         floor};
  ASSERT_EQ(flow.step(in, view, books), "");
  size_t closed = 0;
  for (size_t v = 0; v < nv; ++v) {
    EXPECT_GE(st.mass[v], 0.0) << v;
    EXPECT_GE(flow.volume_used()[v], floor[v] * (1.0 - 1e-12)) << v;
    const double wall_volume = net.volume[v] + open[v] * (flow.wall_pressure()[v] - net.applied[v]);
    EXPECT_NEAR(wall_volume, flow.volume_used()[v], 1e-9 * net.volume[v]) << v;
    if (flow.wall_pressure()[v] != st.pressure[v]) ++closed;
  }
  EXPECT_GT(closed, 0u);  // the case does reach the third stage
  EXPECT_NEAR(st.total_mass() - m0, st.total_exchanged(), 1e-12 * m0);
}

// Zero viscosity: a sealed crack (no fixed vertex) holds one pressure, the equation of state's for its
// total mass in its total volume, whatever the masses' distribution; a second, separate crack keeps its own.
TEST(NetworkFlow, ZeroViscosityGivesOnePressurePerConnectedCrack) {
  const Strip a = make_strip(0.05, 0.05, 4, 4, 0.2, 3);
  Strip both = a;
  const int32_t shift = int32_t(a.vx.size() / 3);
  for (size_t k = 0; k < a.vx.size(); k += 3)
    both.vx.insert(both.vx.end(), {a.vx[k] + 1.0, a.vx[k + 1], 0.0});
  for (int32_t v : a.tri) both.tri.push_back(v + shift);
  RigidNetwork net(both.vx, both.tri, 5e-5);
  const size_t nv = both.vx.size() / 3;
  for (size_t v = 0; v < nv; ++v) net.compliance[v] = v < size_t(shift) ? 1e-16 * double(v % 3) : 0.0;
  VertexState st(nv);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.9, 1.1);
  for (size_t v = 0; v < nv; ++v)
    st.mass[v] = 1000.0 * net.volume[v] * u(rng) * (v < size_t(shift) ? 1.001 : 1.003);
  const double m_first = std::accumulate(st.mass.begin(), st.mass.begin() + shift, 0.0);
  NetworkFlow flow(kWater, 0.0, 0.0);
  flow.set_network(both.tri, nv);
  NetworkFlowBooks books;
  auto view = st.view();
  ASSERT_EQ(flow.step(net.input(1e-6, 1e-6), view, books), "");
  for (int part = 0; part < 2; ++part) {
    const size_t b = part ? size_t(shift) : 0, e = part ? nv : size_t(shift);
    double m = 0, v0 = 0, c = 0;
    for (size_t v = b; v < e; ++v) {
      m += st.mass[v];
      v0 += net.volume[v];
      c += net.compliance[v];
      EXPECT_EQ(st.pressure[v], st.pressure[b]);
      EXPECT_EQ(st.role[v], uint8_t(FlowRole::wet));
    }
    // rho(p) V(p) = m, the equation of state, to rounding.
    const double p = st.pressure[b];
    EXPECT_NEAR(kWater.density(p) * (v0 + c * p), m, 1e-13 * m);
    if (part == 0) {
      EXPECT_NEAR(m, m_first, 1e-13 * m);
    }
  }
  EXPECT_GT(st.pressure[size_t(shift)], st.pressure[0]);  // the second crack was filled denser
}

// A front advancing from a pressure-held well into a dry crack: mass books close to 1e-12 at every step,
// vertices ahead of the front hold the lag pressure, the wet region only grows and stays connected to the
// well, and the wetting times increase along the strip.
TEST(NetworkFlow, FrontAdvancesIntoADryCrackConservingMass) {
  const Strip s = make_strip(0.05, 0.005, 40, 2, 0.25, 11);
  RigidNetwork net(s.vx, s.tri, 2e-5);
  const size_t nv = s.vx.size() / 3;
  VertexState st(nv);
  const double p_well = 5e6, lag = -1e5;
  for (int j = 0; j <= s.ny; ++j) {
    st.role[s.vertex(0, j)] = uint8_t(FlowRole::fixed);
    net.fixed[s.vertex(0, j)] = p_well;
  }
  NetworkFlow flow(kWater, 1e-3, lag);
  flow.set_network(s.tri, nv);
  NetworkFlowBooks books;
  std::vector<double> before;
  size_t wet_before = 0;
  double m0 = st.total_mass();
  const double dt = 2e-4;
  for (int k = 0; k < 200; ++k) {
    auto view = st.view();
    ASSERT_EQ(flow.step(net.input(dt, dt * (k + 1)), view, books), "");
    const double m = st.total_mass();
    EXPECT_NEAR(m - m0, books.sourced + st.total_exchanged(), 1e-12 * std::max(m, 1e-30)) << k;
    size_t wet = 0;
    for (size_t v = 0; v < nv; ++v) {
      wet += st.role[v] == uint8_t(FlowRole::wet);
      if (st.role[v] == uint8_t(FlowRole::dry) || st.role[v] == uint8_t(FlowRole::filling)) {
        EXPECT_EQ(st.pressure[v], lag);
      }
    }
    EXPECT_GE(wet, wet_before);
    wet_before = wet;
  }
  EXPECT_GT(wet_before, nv / 4);  // the front moved
  EXPECT_LT(wet_before, nv);      // and is still inside the strip
  EXPECT_GT(books.dissipation, 0.0);
  // Wetting times grow along the strip's centre line (vertices on the middle row).
  double last = 0.0;
  for (int i = 1; i <= s.nx; ++i) {
    const double t = st.wetting[s.vertex(i, 1)];
    if (t < 0) break;
    EXPECT_GE(t, last) << i;
    last = t;
  }
}

// Conjugate gradients from the last pressure give the factorisation's pressures to their tolerance, and
// the same mass books (the fluxes of whatever pressure the solve returns are conserved exactly).
TEST(NetworkFlow, ConjugateGradientsAgreeWithTheFactorisation) {
  const Strip s = make_strip(0.05, 0.005, 40, 2, 0.25, 11);
  RigidNetwork net(s.vx, s.tri, 2e-5);
  const size_t nv = s.vx.size() / 3;
  VertexState direct(nv), cg(nv);
  for (VertexState* st : {&direct, &cg})
    for (int j = 0; j <= s.ny; ++j) {
      st->role[s.vertex(0, j)] = uint8_t(FlowRole::fixed);
      net.fixed[s.vertex(0, j)] = 5e6;
    }
  NetworkFlow by_ldlt(kWater, 1e-3, -1e5, NetworkSolver::direct),
      by_cg(kWater, 1e-3, -1e5, NetworkSolver::cg);
  by_ldlt.set_network(s.tri, nv);
  by_cg.set_network(s.tri, nv);
  NetworkFlowBooks b1, b2;
  int iterations = 0;
  for (int k = 0; k < 100; ++k) {
    auto v1 = direct.view(), v2 = cg.view();
    ASSERT_EQ(by_ldlt.step(net.input(2e-4, 2e-4 * (k + 1)), v1, b1), "");
    ASSERT_EQ(by_cg.step(net.input(2e-4, 2e-4 * (k + 1)), v2, b2), "");
    iterations += by_cg.cg_iterations();  // 0 while only held vertices exist: the guess is the answer
    EXPECT_NEAR(cg.total_mass(), b2.sourced + cg.total_exchanged(), 1e-12 * cg.total_mass());
  }
  EXPECT_GT(iterations, 100);
  for (size_t v = 0; v < nv; ++v) {
    EXPECT_EQ(cg.role[v], direct.role[v]) << v;
    EXPECT_NEAR(cg.pressure[v], direct.pressure[v], 1e-6 * 5e6) << v;
  }
}

}  // namespace
}  // namespace rift
