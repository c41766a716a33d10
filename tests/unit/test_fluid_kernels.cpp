// P1 fluid element kernels against hand-computed values on the reference tet (0,0,0),(1,0,0),(0,1,0),
// (0,0,1) (V = 1/6, grad N = (-1,-1,-1), e_x, e_y, e_z), identities that hold on any tet (rows of the
// stiffness sum to zero, the mass sums to the volume, the gradient of a linear field is exact), the
// structured box mesh, and the CSR pattern / slot maps.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "engine/linear/csr_matrix.hpp"
#include "engine/mesh/structured_box.hpp"
#include "kernels/fluid_element.hpp"

namespace rift::kernels {
namespace {

constexpr double kRef[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
constexpr double kGeneral[12] = {0.1, -0.2, 0.05, 1.3, 0.1, -0.1, 0.2, 0.9, 0.3, -0.1, 0.25, 1.1};

TEST(FluidKernels, ReferenceTetGradientsAndVolume) {
  double g[12];
  EXPECT_DOUBLE_EQ(p1_gradients(kRef, g), 1.0 / 6.0);
  const double expect[12] = {-1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < 12; ++i) EXPECT_DOUBLE_EQ(g[i], expect[i]) << i;
  EXPECT_DOUBLE_EQ(tet_max_edge(kRef), std::sqrt(2.0));
}

TEST(FluidKernels, ReferenceTetStiffnessByHand) {
  double g[12], k[16];
  const double v = p1_gradients(kRef, g);
  p1_stiffness(v, g, k);
  // V g_a.g_b: K_00 = 3/6, K_0b = -1/6, K_aa = 1/6, K_ab = 0 (a, b >= 1, a != b).
  const double e[16] = {0.5,      -1.0 / 6, -1.0 / 6, -1.0 / 6, -1.0 / 6, 1.0 / 6, 0, 0,
                        -1.0 / 6, 0,        1.0 / 6,  0,        -1.0 / 6, 0,       0, 1.0 / 6};
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(k[i], e[i], 1e-15) << i;
}

TEST(FluidKernels, MassAndStiffnessIdentitiesOnAGeneralTet) {
  double g[12], m[16], k[16];
  const double v = p1_gradients(kGeneral, g);
  ASSERT_GT(v, 0.0);
  p1_mass(v, m);
  p1_stiffness(v, g, k);
  EXPECT_NEAR(std::accumulate(m, m + 16, 0.0), v, 1e-15);
  EXPECT_DOUBLE_EQ(m[0], v / 10.0);
  EXPECT_DOUBLE_EQ(m[1], v / 20.0);
  for (int a = 0; a < 4; ++a) {
    double row = 0.0;
    for (int b = 0; b < 4; ++b) {
      row += k[4 * a + b];
      EXPECT_DOUBLE_EQ(k[4 * a + b], k[4 * b + a]);
    }
    EXPECT_NEAR(row, 0.0, 1e-13);
  }
  // Patch test: for a linear field phi = c + q.x the gradients reproduce q exactly.
  const double q[3] = {0.7, -1.3, 2.1};
  double grad_phi[3] = {0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    const double phi = 0.4 + q[0] * kGeneral[3 * a] + q[1] * kGeneral[3 * a + 1] + q[2] * kGeneral[3 * a + 2];
    for (int d = 0; d < 3; ++d) grad_phi[d] += g[3 * a + d] * phi;
  }
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(grad_phi[d], q[d], 1e-13);
  // An inverted tet gets zero gradients and a negative volume.
  double flipped[12];
  std::copy(kGeneral, kGeneral + 12, flipped);
  std::swap_ranges(flipped + 3, flipped + 6, flipped + 6);
  EXPECT_NEAR(p1_gradients(flipped, g), -v, 1e-15);
  for (double gi : g) EXPECT_EQ(gi, 0.0);
}

TEST(FluidKernels, ConvectionOfALinearFieldIsExact) {
  // int N_a w.grad phi for constant w and linear phi is (V/4) w.q; and for linear w the row sums of C
  // vanish (C applied to a constant is zero).
  double g[12], c[16];
  const double v = p1_gradients(kGeneral, g);
  const double wc[12] = {1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3};
  p1_convection(v, g, wc, c);
  const double q[3] = {0.7, -1.3, 2.1};
  for (int a = 0; a < 4; ++a) {
    double s = 0.0, row = 0.0;
    for (int b = 0; b < 4; ++b) {
      const double phi = q[0] * kGeneral[3 * b] + q[1] * kGeneral[3 * b + 1] + q[2] * kGeneral[3 * b + 2];
      s += c[4 * a + b] * phi;
      row += c[4 * a + b];
    }
    EXPECT_NEAR(s, v / 4.0 * (1 * q[0] + 2 * q[1] + 3 * q[2]), 1e-14);
    EXPECT_NEAR(row, 0.0, 1e-14);
  }
  // Reference tet, w = x e_x (nodal values x_c): C_ab = (V/20)(sum_c x_c + x_a) g_b,x; sum x_c = 1.
  double gr[12], cr[16];
  const double vr = p1_gradients(kRef, gr);
  const double wx[12] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0};
  p1_convection(vr, gr, wx, cr);
  EXPECT_NEAR(cr[4 * 1 + 1], vr / 20.0 * 2.0 * 1.0, 1e-16);  // a = 1 (x_a = 1), b = 1 (g_x = 1)
  EXPECT_NEAR(cr[4 * 0 + 0], vr / 20.0 * 1.0 * -1.0, 1e-16);
  EXPECT_NEAR(cr[4 * 2 + 3], 0.0, 1e-16);
  // Streamline diffusion is symmetric positive semi-definite with the kernel of constants.
  double s[16];
  const double wbar[3] = {0.3, -0.2, 0.9};
  p1_streamline_diffusion(v, g, wbar, 0.5, s);
  for (int a = 0; a < 4; ++a) {
    double row = 0.0;
    for (int b = 0; b < 4; ++b) row += s[4 * a + b];
    EXPECT_NEAR(row, 0.0, 1e-13);
    EXPECT_GE(s[5 * a], 0.0);
  }
}

TEST(FluidKernels, StructuredBoxIsConformingAndPositive) {
  StructuredBoxSpec spec;
  spec.lo = {0.0, -1.0, 0.0};
  spec.hi = {2.0, 1.0, 0.5};
  spec.cells = {4, 3, 2};
  const TetMesh mesh = structured_box(spec);
  ASSERT_EQ(mesh.nodes.size(), 5u * 4u * 3u);
  ASSERT_EQ(mesh.tets.size(), 6u * 24u);
  std::vector<double> x, vol(mesh.tets.size()), grad(12 * mesh.tets.size()), h(mesh.tets.size());
  for (const auto& n : mesh.nodes) x.insert(x.end(), n.begin(), n.end());
  std::vector<int32_t> tn;
  for (const auto& t : mesh.tets) tn.insert(tn.end(), t.begin(), t.end());
  EXPECT_EQ(p1_prepare(x, tn, vol, grad, h), 0u);
  EXPECT_NEAR(std::accumulate(vol.begin(), vol.end(), 0.0), 2.0, 1e-13);
  // Two triangles per boundary cell face; their areas add up to the box faces.
  std::array<double, 6> area{};
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    double e1[3], e2[3];
    for (int d = 0; d < 3; ++d) {
      e1[d] = mesh.nodes[t[1]][d] - mesh.nodes[t[0]][d];
      e2[d] = mesh.nodes[t[2]][d] - mesh.nodes[t[0]][d];
    }
    const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                 cz = e1[0] * e2[1] - e1[1] * e2[0];
    area[mesh.triangle_surface[f]] += 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  }
  const std::array<double, 6> expect{1.0, 1.0, 1.0, 1.0, 4.0, 4.0};
  for (int s = 0; s < 6; ++s) EXPECT_NEAR(area[s], expect[s], 1e-13) << mesh.surface_names[s];
  // Global stiffness: a linear field is in the kernel at interior nodes; rows sum to zero everywhere.
  CsrMatrix k = p1_pattern(static_cast<int32_t>(mesh.nodes.size()), tn);
  const auto slot = p1_tet_slots(k, tn);
  std::vector<double> ones(mesh.tets.size(), 1.0);
  std::vector<uint8_t> fixed(mesh.nodes.size(), 0);
  std::vector<double> value(mesh.nodes.size(), 0.0);
  const auto diag = diagonal_slots(k);
  scalar_laplacian_assemble({tn, vol, grad, ones, slot, diag, fixed, value, k.val, {}});
  std::vector<double> lin(mesh.nodes.size()), y(mesh.nodes.size()), c(mesh.nodes.size(), 1.0);
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
    lin[n] = 1.0 + 2.0 * mesh.nodes[n][0] - mesh.nodes[n][1] + 3.0 * mesh.nodes[n][2];
  k.multiply(c, y);
  for (double yi : y) EXPECT_NEAR(yi, 0.0, 1e-12);
  k.multiply(lin, y);
  for (size_t n = 0; n < mesh.nodes.size(); ++n) {
    const auto& p = mesh.nodes[n];
    const bool interior = p[0] > 0 && p[0] < 2 && p[1] > -1 && p[1] < 1 && p[2] > 0 && p[2] < 0.5;
    if (interior) {
      EXPECT_NEAR(y[n], 0.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace rift::kernels
