#pragma once
// Linear (P1) tetrahedral finite elements for the incompressible fluid (docs/fluid.md). Shape functions
// N_a, a = 0..3, with constant gradients g_a = grad N_a on a tet of volume V (sum_a g_a = 0). With
// exact integration:
//   mass               M_ab = int N_a N_b      = V (1 + delta_ab) / 20      (sum_ab M_ab = V)
//   lumped mass        L_a  = int N_a          = V / 4
//   stiffness          K_ab = int g_a . g_b    = V g_a . g_b                (rows sum to zero)
//   convection         C_ab = int N_a (w . g_b) for the P1 field w with nodal values w_c:
//                           = (V / 20) (sum_c w_c + w_a) . g_b           (int N_a N_c = M_ac)
//   streamline diff.   S_ab = tau V (wbar . g_a)(wbar . g_b),  wbar = mean of w_c (with the projection
//                           below, the orthogonal-subscale convection term:
//                           kernels/fluid_convection_subscale.hpp)
//   gradient           G_ab = int N_a g_b      = (V / 4) g_b   (a vector; also the divergence: the weak
//                           continuity int q div u = sum_b G_ab . u_b)
// Conventions: coordinates, velocities and vectors are 3 doubles per node (x y z), tets 4 node indices,
// per-tet gradients 12 doubles (g_0 .. g_3, x y z each). Assembly writes into the value array of a CSR
// matrix through a slot map: slot[16 t + 4 a + b] is the position of entry (node_a, node_b) of tet t in
// the value array, precomputed once for a fixed sparsity pattern (engine/linear/csr_matrix.hpp), so
// refilling a matrix is one pass over the tets with no search and no allocation.
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

// Gradients g (12 doubles) of the four shape functions and the signed volume det[x1-x0, x2-x0, x3-x0]/6.
// x holds the 12 corner coordinates. A tet with volume <= 0 gets g = 0.
double p1_gradients(const double* x, double* g);

// Longest edge of the tet with corner coordinates x (12 doubles): the element size h of the
// stabilisation parameters.
double tet_max_edge(const double* x);

// Element matrices (row-major 4 x 4) from the formulas above.
void p1_mass(double volume, double* m);
void p1_stiffness(double volume, const double* g, double* k);
void p1_convection(double volume, const double* g, const double* w, double* c);  // w: 12 nodal values
void p1_streamline_diffusion(double volume, const double* g, const double* wbar, double tau, double* s);

// Per-tet geometry of a mesh: volume (1 per tet), gradients (12 per tet), h = longest edge (1 per tet).
// Returns how many tets had volume <= 0.
size_t p1_prepare(std::span<const double> x, std::span<const int32_t> tet_nodes, std::span<double> volume,
                  std::span<double> grad, std::span<double> h);

// Momentum system of one theta step (one Picard iterate), per unit volume terms:
//   rho (u - u^n)/dt + theta L(w) u + (1 - theta) L(w) u^n + sigma (u - u_s) + grad p^* = f + s,
//   L(w) = -mu lap + rho w.grad + streamline diffusion (tau_s = supg_tau[t], 0 = off).
// With convection_projection eta (3 per node) the streamline term is the orthogonal one: the right-hand side
// also gains rho tau_s V (wbar . g_a) etabar (etabar the tet's mean of eta), whole at any theta because eta
// is the projection of w . grad w, w = theta u^k + (1 - theta) u^n.
// Matrix (same for the three components): rho/dt M + theta (mu K + rho C + S) + sigma Lumped.
// Right-hand side (3 per node): (rho/dt M - (1-theta)(mu K + rho C + S)) u^n + sigma Lumped u_s
//   + M f + (V/4) s - G p^*.   The absorption sigma is fully implicit (backward Euler) at any theta.
// matrix_values and rhs are accumulated into (the caller zeroes them). Empty optional spans = zero.
struct FluidMomentumArgs {
  double rho = 1.0, mu = 1.0, dt = 1.0, theta = 1.0;
  std::span<const int32_t> tet_nodes;
  std::span<const double> volume, grad;           // from p1_prepare
  std::span<const int32_t> slot;                  // 16 per tet
  std::span<const double> u_old;                  // u^n, 3 per node
  std::span<const double> advect;                 // w, 3 per node
  std::span<const double> pressure;               // p^*, 1 per node
  std::span<const double> supg_tau;               // tau_s [s], 1 per tet (S uses rho tau_s); may be empty
  std::span<const double> convection_projection;  // eta, 3 per node; empty: plain streamline diffusion
  std::span<const double> sigma;                  // absorption [kg/(m^3 s)], 1 per tet; may be empty
  std::span<const double> target;                 // u_s, 3 per tet; may be empty
  std::span<const double> source;                 // s [N/m^3], 3 per tet; may be empty
  std::span<const double> body_force;             // f [N/m^3], 3 per node (P1 field); may be empty
  std::span<double> matrix_values;
  std::span<double> rhs;  // 3 per node
};
void fluid_assemble_momentum(const FluidMomentumArgs& a);
// Tets [begin, end) only. Ranges whose tets share no node may run at the same time (colouring,
// systems/fluid/fluid_assembly.hpp); each entry then receives its contributions in a fixed order.
void fluid_assemble_momentum(const FluidMomentumArgs& a, size_t begin, size_t end);

// Scalar P1 operator sum_t coef[t] K^t into a symmetric CSR matrix, with Dirichlet rows and columns
// eliminated: rows of nodes with fixed[n] != 0 become identity (rhs = value[n]) and their columns move to
// the right-hand side (rhs_i -= K_in value[n]), so the matrix stays symmetric positive definite.
// diag_slot[n] is the value position of entry (n, n). matrix_values and rhs are accumulated into; the
// Dirichlet rows' rhs are overwritten.
struct ScalarLaplacianArgs {
  std::span<const int32_t> tet_nodes;
  std::span<const double> volume, grad, coef;
  std::span<const int32_t> slot, diag_slot;
  std::span<const uint8_t> fixed;
  std::span<const double> value;
  std::span<double> matrix_values, rhs;  // rhs may be empty (matrix only)
};
void scalar_laplacian_assemble(const ScalarLaplacianArgs& a);
// The Dirichlet column elimination of scalar_laplacian_assemble for the right-hand side alone (the matrix
// unchanged): rhs_i -= sum over tets of coef K_in value[n] for fixed n, free i; fixed rows get value[n].
void scalar_laplacian_dirichlet_rhs(const ScalarLaplacianArgs& a);
// The matrix of scalar_laplacian_assemble in two steps: the entries of free rows and columns of tets
// [begin, end) (accumulated; ranges as for fluid_assemble_momentum), then, once, the fixed rows' unit
// diagonal (scalar_laplacian_fix_rows: uses fixed, diag_slot, matrix_values).
void scalar_laplacian_matrix(const ScalarLaplacianArgs& a, size_t begin, size_t end);
void scalar_laplacian_fix_rows(const ScalarLaplacianArgs& a);

// Right-hand side of the pressure-correction equation (docs/fluid.md):
//   rhs_q = -sum_t [ w_t (V/4) div u*_t  +  tau_p[t] V g_q . (grad p_t - xibar_t)
//                    + h_t V g_q . (grad p_t - fbar_t) ]
// with div u*_t and grad p_t the (constant) cell divergence and pressure gradient, xibar_t the mean of
// the nodal projected pressure gradient xi (3 per node), w_t the continuity's weight (1 when div_weight
// is empty), h_t the coefficient of a Darcy-like flux that takes its place (0 when relative_flux is empty)
// and fbar_t the mean of the nodal body force (3 per node; zero when body_force is empty). Accumulated
// into rhs.
void fluid_pressure_rhs(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                        std::span<const double> grad, std::span<const double> u, std::span<const double> p,
                        std::span<const double> xi, std::span<const double> tau_p, std::span<double> rhs);
// The same for tets [begin, end) (ranges as for fluid_assemble_momentum).
struct FluidPressureRhsArgs {
  std::span<const int32_t> tet_nodes;
  std::span<const double> volume, grad, u, p, xi, tau_p;
  std::span<const double> div_weight = {}, relative_flux = {};  // per tet; empty: 1 and 0
  std::span<const double> body_force = {};                      // 3 per node; empty: 0
};
void fluid_pressure_rhs(const FluidPressureRhsArgs& a, std::span<double> rhs, size_t begin, size_t end);

// Cell divergence div u_t = sum_a g_a . u_a (1 per tet).
void p1_divergence(std::span<const int32_t> tet_nodes, std::span<const double> grad,
                   std::span<const double> u, std::span<double> div);

// Lumped L2 projection of the cell gradient of a P1 scalar p weighted by w[t] (w empty = 1):
//   out_n = sum_t (V/4) w_t grad p_t   (3 per node, accumulated; the caller divides by its nodal weights).
void p1_weighted_gradient(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                          std::span<const double> grad, std::span<const double> p, std::span<const double> w,
                          std::span<double> out);
// The same for tets [begin, end) (ranges as for fluid_assemble_momentum).
struct WeightedGradientArgs {
  std::span<const int32_t> tet_nodes;
  std::span<const double> volume, grad, p, w;
};
void p1_weighted_gradient(const WeightedGradientArgs& a, std::span<double> out, size_t begin, size_t end);

}  // namespace rift::kernels
