#pragma once
// Critical time step of the explicit (central-difference) solid for 4-node tets.
//
// Elastic limit per tet (femdem.md 1d, line 304: "dt <= alpha h_min / c_p, c_p = sqrt((lambda + 2 mu)/rho)"):
//   dt_e = h / c_p,  h = smallest altitude = 3 V / (largest face area),  c_p = sqrt((lambda + 2 mu) / rho).
// These functions return the limit itself (alpha = 1); the caller applies its safety factor alpha.
//
// Viscous reduction. femdem.md 1d gives no step formula for it, only the size of the Y damping coefficient
// (line 321): "eta = 2 h beta sqrt(E rho), 0 < beta < 1 (beta = 1 ≈ critical for the element's highest
// mode)". Turned into a step limit here [D]: the highest element mode has omega = 2 / dt_e; the term eta D
// acts on it as a dashpot against the P-wave modulus M = lambda + 2 mu (Kelvin-Voigt), so its damping ratio
// is
//   xi = omega eta / (2 M) = eta / (M dt_e).
// Leapfrog with the damping force taken from v(t - dt/2) (how central_difference.hpp is used) is stable for
//   omega dt <= 2 (sqrt(1 + xi^2) - xi)
// (Jury test on the 2x2 amplification matrix, trace 2 - w^2 - 2 xi w, det 1 - 2 xi w, w = omega dt; the same
// bound as Belytschko, Liu & Moran 2000, sec. 6.2, for the averaged-velocity form). Hence
//   dt = dt_e (sqrt(1 + xi^2) - xi) = sqrt(dt_e^2 + a^2) - a,  a = eta / M.
// Check against the femdem.md line: eta = 2 h beta sqrt(E rho) gives xi = 2 beta sqrt(E / M), i.e. 1.83 beta
// for nu = 0.25, so beta = 1 is about twice critical by this estimate: same scaling, factor ~2 apart.
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/tet_forces.hpp"

namespace rift::kernels {

// min over tets [begin, end) of h / c_p, on positions x (3 per node). material: 1 per tet into materials;
// density: 1 per material [kg/m3], parallel to materials. Tets with volume <= 0 are skipped (tet_prepare
// reports them, tet_forces ignores them). Returns +infinity when no tet qualifies.
double tet_stable_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                       std::span<const int32_t> material, std::span<const TetMaterial> materials,
                       std::span<const double> density, size_t begin, size_t end);

// The viscous reduction above for one elastic limit dt_e: sqrt(dt_e^2 + a^2) - a with a = eta / p_modulus
// (p_modulus = lambda + 2 mu). Evaluated as dt_e^2 / (sqrt(dt_e^2 + a^2) + a) to avoid cancellation.
double viscous_stable_step(double dt_elastic, double eta, double p_modulus);

// min over tets of viscous_stable_step(h / c_p, eta, lambda + 2 mu), each tet with its own material.
// With one material this equals viscous_stable_step(tet_stable_step(...), eta, lambda + 2 mu), because the
// reduction increases with dt_e; with several it can pick a different tet.
double tet_damped_stable_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                              std::span<const int32_t> material, std::span<const TetMaterial> materials,
                              std::span<const double> density, size_t begin, size_t end);

}  // namespace rift::kernels
