#pragma once
// The dynamic pressure subscale of the orthogonal-subscale stabilisation (Codina, Principe, Guasch &
// Badia, CMAME 196 (2007) 2413-2430, "time dependent subscales"). Per tet, the velocity subscale u' that
// the P1 velocity cannot represent obeys
//   rho du'/dt + u' / tau = -(grad p - xibar),   tau = 1 / (4 mu/h^2 + 2 rho |w|/h + sigma),
// xibar the tet's mean of the lumped projection of grad p. Backward Euler over the fluid step:
//   u'^{n+1} = tau_t (rho/dt u'^n - (grad p^{n+1} - xibar^{n+1})),   tau_t = 1 / (rho/dt + 1/tau).
// The continuity equation's -int grad q . u' is then the implicit tau_t (grad q, grad p - xibar) (the
// quasi-static form with tau_t for tau) and the explicit term of pressure_subscale_rhs. Why: tau_t <= dt/rho
// keeps the pressure Schur complement within reach of its preconditioner at any viscosity (the quasi-static
// tau = h^2 / (4 mu) of water at rest is 1e6 x dt/rho, and FGMRES stalled), while at a steady state
// u'^{n+1} = u'^n gives u' = -tau (grad p - xibar): the steady solution does not depend on dt.
#include <cstdint>
#include <span>

namespace rift::kernels {

struct PressureSubscaleArgs {
  std::span<const int32_t> tet_nodes;  // 4 per tet
  std::span<const double> volume;      // 1 per tet
  std::span<const double> grad;        // 12 per tet: gradients of the four shape functions
  std::span<const double> tau_t;       // 1 per tet: 1 / (rho/dt + 1/tau)
  double rho_over_dt = 0.0;
};

// rhs_q += sum_t tau_t rho/dt V g_q . u'_t (the subscale's memory in -R; accumulated, 1 per node).
void pressure_subscale_rhs(const PressureSubscaleArgs& a, std::span<const double> subscale,
                           std::span<double> rhs);

// u'_t <- tau_t (rho/dt u'_t - (grad p_t - xibar_t)) with p (1 per node) and xi (3 per node) of the new
// level: the subscale at the end of a step (3 per tet, in place).
void pressure_subscale_update(const PressureSubscaleArgs& a, std::span<const double> p,
                              std::span<const double> xi, std::span<double> subscale);

}  // namespace rift::kernels
