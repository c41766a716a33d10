#pragma once
// Tet-tet contact forces: Munjiza's distributed potential (femdem.md 1c, Y3D's Yid3TET2TET as described
// there), with a Coulomb friction and an optional normal viscous term added per pair.
//
// Potential. Each tet carries phi = 1 at its centroid g, 0 on its boundary, linear in each of the 4 centroid
// sub-tets (face j + g, face j opposite corner j): phi(x) = 4 min_j B_j(x) inside (B_j the tet's barycentric
// coordinates; B_j(g) = 1/4), 0 outside. For contactor c and target t the force on c is
//   f_c = p ∫_{c∩t} (grad phi_c - grad phi_t) dV = -p ∫_{∂c ∩ t} n_c phi_t dA + p ∫_{∂t ∩ c} n_t phi_c dA,
// n the outward normals (phi_c = 0 on ∂c, phi_t = 0 on ∂t turn the volume integral into these two boundary
// terms). The first term is "c as contactor, t as target", the second the same with the roles swapped:
// each pair is processed both ways, and the force on t is the negative of the force on c.
//
// One way (contactor C, target T). For each of C's 4 faces (outward unit normal n) and each of T's 4
// sub-tets S_j: the polygon P = face triangle ∩ S_j (femdem.md 1c, steps 2-3: the section of S_j by the face
// plane, clipped to the face triangle; here one Sutherland-Hodgman routine clips the triangle by half-spaces
// instead, which gives the same polygon). Everything is carried in T's barycentric coordinates B_0..B_3: the
// triangle is clipped once by T's faces (B_i >= 0), then per sub-tet by its 3 inner planes (B_i >= B_j);
// on S_j the sub-tet coordinates are L_i = B_i - B_j (i != j) and L_g = 4 B_j = phi_T. phi_T is linear on
// P, so (fanning P into triangles, exact):
//   I = ∫_P phi_T dA = sum A_k (phi_0 + phi_k + phi_{k+1}) / 3,  m = ∫_P x phi_T dA = sum A_k / 12
//   (sum_v phi_v x_v + (sum_v phi_v)(sum_v x_v)),   force centre x_F = m / I,   F = p I.
// The load -p phi_T n on C's face and +p phi_T n on S_j are distributed consistently (∫ N_i phi dA =
// N_i(x_F) I for any affine N_i; femdem.md 1c, step 4): C's corners get -F n times C's barycentric
// coordinates at x_F (the face's, as x_F lies on the face; the opposite corner's is 0 to round-off); S_j's
// corners get +F n times L_i(x_F) and g_T's share L_g is split 1/4 to each of T's corners, which adds up to
// exactly T's barycentric coordinates: corner i gets +F n B_i(x_F).
//
// Properties (tests/unit/test_contact_potential.cpp). Every contribution is a force F n and its opposite,
// both placed at x_F (the distributions reproduce x_F: sum N_i x_i = x_F), so the 8 corner forces sum to zero
// and their moment about any point is zero, each to round-off. For a rigid translation u of one tet
// the total force is exactly -dE/du with the overlap energy
//   E = p ∫_{c∩t} (phi_c + phi_t) dV
// (Reynolds on the two boundary terms above), and likewise the moment about any point is -dE/dtheta for a
// rigid rotation (each contribution sits at its phi-weighted centre x_F), so the work round a closed path
// of rigid motions is zero: conservative for any p, as femdem.md 1c states. For deforming tets phi moves
// with the nodes and the corner forces are not -dE/dx_corner (on random overlapping pairs they differ by
// 10-50 % of the largest corner force).
// E from the same polygons: in each sub-tet phi - 1 is linear and 0 at g, so G = (x - g)(phi / 4 + 1 / 12)
// is continuous with div G = phi, and ∫_{c∩t} phi_c dV = ∮_{∂(c∩t)} G_c . n dA. ∂(c∩t) is made of the
// polygons of both ways; on C's face polygons phi_C = 0 and (x - g_C).n = h (the face's distance from g_C),
// so each polygon adds p ∫_P [h / 12 + (x - g_T).n (phi_T / 4 + 1 / 12)] dA, a quadratic integrand
// integrated exactly with the same fan (∫ u w dA = A / 12 (sum u_v w_v + sum u_v sum w_v) on a triangle).
// tet_potential() gives phi for tests.
// Contactor faces lying exactly in a plane between two target sub-tets are counted in both (measure zero in
// motion; faces in a target *face* plane get phi_T = 0, so touching neighbours give no force: barycentric
// coordinates within 1e-12 of 0 at the contactor face corners are set to 0 for that).
//
// Friction and damping (per pair, on top of the potential). With F_A the total potential force on tet A
// (A = pair.a), the pair's normal is n = F_A / |F_A| (from B into A), f_n = |F_A|, and its contact point x_c
// is the F-weighted mean of all the force centres of both ways. v_rel = v_A(x_c) - v_B(x_c), each tet's
// velocity interpolated linearly (its barycentric coordinates at x_c, extrapolated when x_c lies outside).
//   friction: coulomb_friction_update below, with du = v_rel dt and f_n the potential's normal force (below);
//   normal damping (femdem.md 1c's viscous contact, with a per-pair coefficient eta_n [N s/m] chosen by the
//   caller, e.g. eta_n = 4 xi sqrt(p / rho) A_c / h for the viscous stress 4 xi sqrt(p/rho) d_dot / h on an
//   area A_c; scaled per pair, below): f_d = -eta_n (v_rel . n) n on A, limited so that the total normal
//   force on A stays >= 0 (no adhesion); its dissipation is -f_d . v_rel dt >= 0.
// Pair stiffness. k_pair = sum over the polygons of p A_P |grad phi_T| (phi_T's gradient in the polygon's
// sub-tet, 4 |grad B_j|): the normal stiffness the pair has as it stands, which grows from 0 as two tets
// start to touch (8 p A / H for two equal tets face to face over an area A, H the tets' height over it).
// With law.reference_stiffness = k_ref > 0, the pair's eta_n is the law's times k_pair / k_ref: damping
// then scales with the pair's share of the contact, so a mesh that splits one contact into more pairs (or
// pairs that barely touch) adds no damping, and eta_n / k_pair is the same for every pair, so a node's
// damping ratio is set by its stiffest mode (the stable step accounts for it: ContactSystem). A pair that
// barely touches with the full eta_n instead pushes far harder than its overlap while approaching and may
// pull only up to its potential force: on a vibrating contact this one-sided push lifts the block off its
// friction, and on fine meshes (many pairs per node) the explicit damping alone went unstable. k_t is not
// scaled: the friction history is a force, and a spring that softened under it would release more than it
// stored. The friction cap is mu times the potential's normal force f_n, the dashpot apart (the linear
// contact model's slip condition in DEM, Cundall & Strack 1979). A cap on f_n plus the damping force
// makes friction follow the normal velocity: on a block sliding near its tipping limit (45 degrees,
// mu 0.8) that feedback fed a 50-66 Hz rocking (the block's vertical velocity 7-9 mm/s rms against
// 1.4 mm/s with this cap) and moved the acceleration by -2 to +6 % as the step changed; with this cap
// it is within 0.6 % of g (sin - mu cos) at safety 0.5 and 0.25 (docs/validation.md). In a steady slide
// the damping force averages to zero, so friction / normal is mu on average either way.
// Friction and damping forces go to A's corners by A's barycentric coordinates at x_c and their opposite to
// B's by B's, so they keep both the force and the moment balance. Pairs with F_A = 0 get zero force and
// their friction history is reset (contact lost).
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/contact_broad_phase.hpp"

namespace rift::kernels {

struct ContactLaw {
  double penalty = 0.0;               // p [Pa] (femdem.md 1d for values)
  double friction = 0.0;              // mu >= 0 [-]
  double tangential_stiffness = 0.0;  // k_t [N/m] per pair; 0 disables friction (history unused)
  double normal_damping = 0.0;        // eta_n [N s/m] per pair; 0 disables it
  double reference_stiffness = 0.0;   // k_ref [N/m]: eta_n is that of a pair of this stiffness (each
                                      // pair's scaled by k_pair / k_ref); 0: the same eta_n for every pair
};

// The potential force of one tet pair, both ways (no friction, no damping).
struct TetPairForce {
  double f[8][3];    // corner forces [N]: 0-3 on tet A's corners, 4-7 on tet B's
  double normal[3];  // sum of A's corner forces, F_A [N]
  double centre[3];  // x_c, the F-weighted mean force centre (valid when weight > 0)
  double weight;     // sum of the contributions' F [N]: 0 when the tets do not overlap
  double energy;     // E = p ∫_{A∩B} (phi_A + phi_B) dV [J] (see above)
  double stiffness;  // k_pair = sum of p A_P |grad phi| over the polygons, both ways [N/m]
  int polygons;      // number of non-empty (face, sub-tet) polygons
};

// a, b: the 4 corners of each tet (either orientation; degenerate tets give zero force). penalty: p.
TetPairForce tet_pair_potential_force(const double a[4][3], const double b[4][3], double penalty);
// Each tet with its own penalty: the way "a's faces in b's potential" is scaled by b's, the other by a's,
// i.e. E = p_a ∫ phi_a + p_b ∫ phi_b over the overlap. Still exact force and moment balance, and
// conservative for rigid motions as above (each term is).
TetPairForce tet_pair_potential_force(const double a[4][3], const double b[4][3], double penalty_a,
                                      double penalty_b);

// phi of the tet at x: 4 min_j B_j(x), 0 outside (and for a degenerate tet).
double tet_potential(const double tet[4][3], const double x[3]);

// Coulomb friction with an elastic tangential penalty, one pair, one step (backward-Euler return mapping).
//   history: in/out, 3 doubles, global frame: the tangential (elastic) friction force on A [N], 0 at first
//            contact. It is first turned into the current tangent plane (component along n removed, length
//            kept) so that a rotating contact keeps its stored force.
//   n: unit normal; f_n >= 0 the normal force; du: relative displacement increment of A with respect to B at
//   the contact point over the step (its normal part is ignored); k_t > 0, mu >= 0.
// Trial force  f* = history - k_t du_t.  Cap c = mu f_n.
//   |f*| <= c: stick, f = f*, no dissipation;
//   |f*| >  c: slip, f = c f* / |f*| (the history is rescaled to the cap), slip distance s = (|f*| - c) / k_t
//              (the part of du_t not taken up elastically), dissipation = c s.
// Returns the force on A (= the new history); B gets its opposite.
struct FrictionStep {
  double force[3];
  double dissipation;  // [J], >= 0
  bool slip;
};
FrictionStep coulomb_friction_update(double history[3], const double n[3], double f_n, const double du[3],
                                     double k_t, double mu);

struct ContactArgs {
  std::span<const double> x;           // current positions, 3 per node
  std::span<const double> v;           // velocities, 3 per node; may be empty when k_t = 0 and eta_n = 0
  std::span<const int32_t> tet_nodes;  // 4 per tet
  std::span<const ContactPair> pairs;  // from contact_broad_phase
  ContactLaw law;
  double dt = 0.0;               // step [s], for the friction increment and the dissipation
  std::span<double> history;     // in/out, 3 per pair: friction history; may be empty when k_t = 0
  std::span<double> pair_force;  // out, 24 per pair: A's corners 0-3 then B's corners 0-3 (tet_nodes
                                 // order), x y z each; a gather adds them to the nodes in pair order
  // Optional outputs, 1 per pair; an empty span skips that output.
  std::span<double> normal_force = {};          // f_n = |F_A| [N]
  std::span<double> friction_dissipation = {};  // this step's frictional dissipation [J]
  std::span<double> damping_dissipation = {};   // this step's normal-damping dissipation [J]
  std::span<double> energy = {};                // overlap energy E of the potential [J]
  std::span<double> friction_energy = {};       // elastic energy in the friction spring |h|^2 / (2 k_t) [J]
  std::span<const double> tet_penalty = {};     // p per tet [Pa]; empty: law.penalty for every tet
};

struct ContactStatus {
  size_t touching = 0;  // pairs with a non-zero potential force
  size_t sliding = 0;   // of which slipped in this step
  ContactStatus& operator+=(const ContactStatus& o) {
    touching += o.touching;
    sliding += o.sliding;
    return *this;
  }
};

// Pairs [begin, end). Each pair writes only its own slots (pair_force, history, optional outputs), so
// ranges may be split arbitrarily between threads and the result does not depend on the split. No
// allocation.
ContactStatus contact_forces(const ContactArgs& args, size_t begin, size_t end);

// After a re-detection: each pair's friction history (3 doubles) moves from the old list to the new one;
// pairs only in the new list start at 0, pairs only in the old list are dropped. Both lists sorted
// lexicographically (as contact_broad_phase returns them): one linear merge, no allocation. new_history
// must not overlap old_history.
void remap_pair_history(std::span<const ContactPair> old_pairs, std::span<const double> old_history,
                        std::span<const ContactPair> new_pairs, std::span<double> new_history);

// Sequential gather: node_force[3 node + k] += the pair forces of pairs [0, pairs.size()) in pair order
// (deterministic). node_force is not cleared.
void contact_gather(std::span<const ContactPair> pairs, std::span<const int32_t> tet_nodes,
                    std::span<const double> pair_force, std::span<double> node_force);

}  // namespace rift::kernels
