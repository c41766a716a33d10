#pragma once
// The convective part of the orthogonal-subscale stabilisation (Codina, CMAME 190 (2000) 1579-1599; the
// projection form of Codina & Blasco 1997). The streamline term of SUPG,
//   int rho tau_c (w . grad N_a) (w . grad u),
// is consistent only with the rest of the residual beside it (time derivative, pressure, viscous and body
// terms); without them it adds O(h) diffusion that stays in the steady state. The orthogonal form keeps
// only the part of the convective derivative that the P1 space cannot represent:
//   int rho tau_c (w . grad N_a) (w . grad u - eta),   eta = lumped L2 projection of w . grad u onto P1,
// which vanishes wherever w . grad u is (nodally) linear, so the stabilised solution converges at the
// Galerkin rate. With tau_c free of dt,
//   tau_c = [ (2 |w| / h)^2 + (4 nu / h^2)^2 + (sigma / rho)^2 ]^-1/2   [s],
// a converged steady state does not depend on the time step. eta is lagged one Picard iteration (it is
// computed from the advecting velocity w = theta u^k + (1 - theta) u^n, the iterate the matrix is built
// on), so a converged step satisfies the stabilised equations exactly.
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

// tau_c of the formula above for one tet; 0 for a fluid at rest without viscosity or absorption.
double convection_subscale_tau(double speed, double h, double nu, double sigma_over_rho);

// out_n = sum_t (V_t / 4) (wbar_t . grad w_t) over the tets around node n (3 per node, accumulated; the
// caller divides by its nodal volumes sum_t V_t / 4 to get eta). wbar_t is the tet's mean of w, grad w_t
// the (constant) cell gradient of the P1 field w (3 per node).
void convective_derivative_projection(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                                      std::span<const double> grad, std::span<const double> w,
                                      std::span<double> out);
// The same for tets [begin, end): ranges whose tets share no node may run at the same time (the fluid
// assembly's colouring); each node then receives its contributions in a fixed order.
void convective_derivative_projection(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                                      std::span<const double> grad, std::span<const double> w,
                                      std::span<double> out, size_t begin, size_t end);

}  // namespace rift::kernels
