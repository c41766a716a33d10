#pragma once
// The two halves of the immersed-solid exchange (fluid.md 1.2-1.4 and 1.11), over the candidate pairs
// (fluid tet K, solid tet S) of coupling_broad_phase (volume_fraction.hpp), sorted by K:
//
//   solid -> fluid (before the fluid step):
//     V_KS = |K ∩ S| per pair (exact clipping, tet_intersection.hpp);
//     |K ∩ Omega_s| = sum_S V_KS,  alpha_K = |K ∩ Omega_s| / |K| (clamped to [0, 1]);
//     u_s,K = sum_S V_KS ubar_S / sum_S V_KS (ubar_S: the mean of S's node velocities);
//     sigma_K = beta rho_f alpha_K / dt: the implicit absorption that relaxes the flow inside the solid
//     to the solid's velocity (beta = 1 halves the slip in one step);
//     s_K = sum_S V_KS theta_S / |K| (theta_S = (V_S - V_S^prev) / (dt V_S), S's volume change over the
//     last window of solid steps: the mean over the window, not a sample of the elastic ringing that the
//     window's many solid steps resolve): the solid's rate of volume change per unit volume of K, the
//     divergence the fluid's continuity must allow where the solid is (fluid.md 1.2: a compressible solid in
//     an incompressible mixture is "modelled through time variations of a volume fraction"). Without it, a
//     solid that breathes (elastic waves, an opening crack) pumps pressure into the whole fluid.
//   fluid -> solid (after it): the force of the fluid on the part K ∩ S of the solid,
//     F_KS = w_K V_KS [ beta rho_f / dt (ubar_K - u_s,K)  +  rho_f (ubar_K - ubar_K^old) / dt  -  f ],
//     ubar_K the mean of K's node velocities after the step, ubar_K^old before it, f the fluid body force
//     per unit volume, w_K = min(1, |K| / |K ∩ Omega_s|) (1 unless solid tets overlap). This is the traction
//     of the surrounding fluid on the solid's surface, read off the momentum balance of the fictitious fluid
//     inside the solid (Uhlmann 2005, J. Comput. Phys. 209): traction = absorption it felt + its momentum
//     change - its body force. In a fluid at rest it is Archimedes' buoyancy, -f |S|.
//
// Newton's third law, exactly: the fluid's lumped absorption over K is sigma_K (|K|/4) sum_a (u_a - u_s,K)
// = beta rho_f / dt alpha_K |K| (ubar_K - u_s,K), which is minus the sum over S of the penalty part of
// F_KS, also where the clamp acts (w_K).
//
// Determinism: every output row is written by one call from its own inputs in a fixed order, so ranges
// may be split between threads freely; gather_solid_node_forces is sequential in pair order.
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/volume_fraction.hpp"

namespace rift::kernels {

// Mean of the 4 corner values of each tet in [begin, end): out[3 t + d] = sum_a value[3 n_a + d] / 4.
void tet_mean_vectors(std::span<const double> node_value, std::span<const int32_t> tet_nodes,
                      std::span<double> out, size_t begin, size_t end);

// Mean volumetric strain rate of each tet in [begin, end) since the previous call:
// theta = (V - V_prev) / (dt V) from positions x (3 per node); volume_prev (in/out, 1 per tet) becomes V.
// 0 for a degenerate tet.
void tet_volume_rates(std::span<const double> x, std::span<const int32_t> tet_nodes, double dt,
                      std::span<double> volume_prev, std::span<double> theta, size_t begin, size_t end);

struct OverlapArgs {
  std::span<const double> fluid_x;           // fluid node positions, 3 per node
  std::span<const int32_t> fluid_tet_nodes;  // 4 per fluid tet
  std::span<const double> solid_x;           // solid node positions, 3 per node
  std::span<const int32_t> solid_tet_nodes;  // 4 per solid tet
  std::span<const CouplingPair> pairs;
  std::span<double> volume;  // out, 1 per pair: V_KS [m^3]
};

// Pairs [begin, end).
void overlap_volumes(const OverlapArgs& a, size_t begin, size_t end);

// first[K] = the first pair of fluid tet K, first[n_fluid] = pairs.size() (pairs sorted by fluid tet).
void pair_ranges(std::span<const CouplingPair> pairs, std::span<int64_t> first);

struct SolidToFluidArgs {
  double rho = 0.0;                          // fluid density [kg/m^3]
  double beta = 1.0;                         // absorption weight
  double dt = 0.0;                           // fluid step [s]
  std::span<const double> fluid_volume;      // |K|, 1 per fluid tet
  std::span<const CouplingPair> pairs;       // sorted by fluid tet
  std::span<const int64_t> first;            // pair_ranges
  std::span<const double> pair_volume;       // V_KS
  std::span<const double> solid_velocity;    // ubar_S, 3 per solid tet
  std::span<const double> solid_dilatation;  // theta_S, 1 per solid tet (tet_volume_rates); may be empty
  // out, per fluid tet: |K ∩ Omega_s| (1), alpha_K (1), u_s,K (3; 0 where there is no solid), sigma_K (1),
  // and the weight of K's pairs in the force, min(1, |K| / sum_S V_KS) (1): below 1 only where solid tets
  // overlap (joints in compression interpenetrate a little), so that the clamped alpha and the pairs'
  // force still balance exactly; s_K (1), weighted the same way (may be empty, with solid_dilatation).
  std::span<double> solid_volume, fraction, target, sigma, pair_weight, dilatation;
};

// Fluid tets [begin, end).
void solid_to_fluid_cells(const SolidToFluidArgs& a, size_t begin, size_t end);

struct FluidToSolidArgs {
  double rho = 0.0, beta = 1.0, dt = 0.0;
  double body_force[3] = {0.0, 0.0, 0.0};  // f [N/m^3]
  std::span<const CouplingPair> pairs;
  std::span<const double> pair_volume;         // V_KS
  std::span<const double> fluid_velocity;      // ubar_K after the fluid step, 3 per fluid tet
  std::span<const double> fluid_velocity_old;  // ubar_K before it
  std::span<const double> target;              // u_s,K the step relaxed to
  std::span<const double> pair_weight;         // per fluid tet (SolidToFluidArgs::pair_weight)
  std::span<double> penalty;                   // out, 3 per pair: the penalty part of F_KS [N]
  std::span<double> force;                     // out, 3 per pair: F_KS [N]
};

// Pairs [begin, end).
void fluid_to_solid_pairs(const FluidToSolidArgs& a, size_t begin, size_t end);

// node_value (`components` per solid node) = sum over pairs, in pair order, of a quarter of the pair's
// value on each corner of S (lumped: the consistent load of a uniform density on a linear tet): the force
// F_KS (3), or the virtual added mass (1); components is 3 or 1. Overwrites node_value.
void gather_to_solid_nodes(std::span<const CouplingPair> pairs, std::span<const double> pair_value,
                           int components, std::span<const int32_t> solid_tet_nodes,
                           std::span<double> node_value);

// P1 interpolation of a nodal field at points (the fluid's pressure at the centroids of wetted solid faces).
// candidates: pairs (point, fluid tet) whose boxes overlap, sorted by point: coupling_broad_phase with the
// points as its first side (zero-size boxes) and the fluid tets as its second. Per point the candidate
// whose smallest barycentric coordinate is largest wins (the containing tet; the first in id order on a
// shared face), out[k] = sum_a lambda_a field[n_a]. A point with no candidate, or outside every
// candidate by more than 1e-9 in barycentric terms, gets 0; their number is returned. cell (optional, 1
// per point): the winning tet, -1 for a point outside.
size_t interpolate_p1_at_points(std::span<const double> fluid_x, std::span<const int32_t> fluid_tet_nodes,
                                std::span<const double> field, std::span<const double> points,
                                std::span<const CouplingPair> candidates, std::span<double> out,
                                std::span<int32_t> cell = {});

}  // namespace rift::kernels
