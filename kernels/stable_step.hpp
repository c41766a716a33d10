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

// The largest eigenvalue of M^-1 K_e for one tet (corners c, positively oriented) with its own lumped mass
// rho V / 4 on each corner and K_e = V B^T D B, the Y3D law's tangent at rest [1/s^2]; 0 if V <= 0. This is
// the tet's exact highest squared frequency, which h / c_p above only estimates: on the general tet of the
// tests it is 2.15 x (2 c_p / h)^2, so a lone tet's true step is 1.47 x shorter than dt_e. In a continuous
// mesh the assembled frequencies lie below the elements' (and h / c_p is the usual, adequate estimate); a
// tet of private nodes (a fracture zone) vibrates at its own.
double tet_highest_omega2(const double c[4][3], const TetMaterial& m, double density);

// min over tets [begin, end) of their exact step 2 / sqrt(tet_highest_omega2), reduced by their damping as
// tet_damped_stable_step does; +infinity when no tet has a positive volume.
double tet_exact_stable_step(std::span<const double> x, std::span<const int32_t> tet_nodes,
                             std::span<const int32_t> material, std::span<const TetMaterial> materials,
                             std::span<const double> density, size_t begin, size_t end);

// Per-node stiffness of the bound used with mass scaling: node n's highest frequency is taken as
// omega_n^2 = K_n / m_n, where K_n sums what every element puts on the node. A tet of step dt (the one the
// solid's stable step uses: exact for a tet of private nodes, the h / c_p estimate for one of shared nodes)
// contributes omega_e^2 = (2 / dt)^2 times the mass it lumps on each corner, rho V / 4: K_n += rho V / dt^2
// on its 4 nodes. Heavier corners only lower every Rayleigh quotient, so for a tet alone max_n K_n / m_n
// bounds its frequency for any masses >= rho V / 4. tet_step, tet_mass (rho V): 1 per tet; a tet whose step
// is not finite (degenerate) adds nothing. stiffness: 1 per node, added to (the caller zeroes it); the
// joints and contact add theirs (add_joint_node_stiffness, ContactSystem::node_stiffness) before
// scale_masses_to_step.
void add_tet_node_stiffness(std::span<const int32_t> tet_nodes, std::span<const double> tet_step,
                            std::span<const double> tet_mass, std::span<double> stiffness);

// Selective mass scaling: every node whose own step 2 sqrt(m_n / K_n) is below `step` gets the mass that
// brings it to `step`, m_n = K_n step^2 / 4; the others keep theirs. mass and inv_mass (1 per node) are
// updated in place. Returns the mass added [kg] and the node with the largest factor m_new / m_old (-1 if
// none changed).
struct MassScaling {
  double added = 0.0;       // [kg]
  size_t scaled_nodes = 0;  // nodes made heavier
  double largest_factor = 1.0;
  int64_t largest_node = -1;
};
MassScaling scale_masses_to_step(std::span<const double> stiffness, double step, std::span<double> mass,
                                 std::span<double> inv_mass);

// min over nodes of 2 sqrt(m_n / K_n) (+infinity where K_n = 0 or m_n = 0).
double node_stable_step(std::span<const double> stiffness, std::span<const double> mass);

}  // namespace rift::kernels
