#pragma once
// Forces of 6-node joint (cohesive) elements between tets, per joint per step, current configuration
// (femdem.md 1b, Lei's Yfd3JOINTSL with Guo's additions; the law itself is in joint_law.hpp).
//
// Topology and sign convention. Nodes 0, 1, 2 lie on side A, nodes 3, 4, 5 on side B, node i + 3 facing
// node i. Per joint:
//   xm_i = (x_i + x_{i+3}) / 2       mid-surface triangle          d_i = x_i - x_{i+3}   (A minus B)
//   n    = (xm_1 - xm_0) x (xm_2 - xm_0) / |...|,  A = |...| / 2,  h = shortest edge of the mid-surface
// The corner order must make n point from side B into side A. Reversing tet A's outward face order does
// exactly that (femdem.md 1b, insertion), so with that insertion:
//   opening o = d.n > 0  <=>  the two sides separate,  o < 0  <=>  they interpenetrate.
// At each integration point q (joint_rule.hpp): d = sum N_i d_i, o = d.n, sliding vector sv = d - o n,
// s = |sv|; the law gives sigma, tau and the traction t = sigma n + tau sv / s (no shear term when s = 0).
// Corner forces: f_{A,i} = -sum_q w_q A N_i t,  f_{B,i} = +sum_q w_q A N_i t, so tractions resist the
// separation (sigma > 0 pulls A back towards B). Each facing pair gets the same number with both signs, so
// the six forces sum to zero exactly; only f_B is written (corner_force). Their moment, -sum_i d_i x F_i, is
// not zero once the joint is open (the pair members sit d_i apart), as in Y. The geometric terms of the
// variation (dn/dx, dA/dx, dh/dx) are not included, as in Y: the forces are the tractions lumped, not the
// exact gradient of the stored energy when the mid-surface stretches or turns under load.
//
// Initial (in-situ) offset, optional: a vector o0 per joint (global frame) added to every d_i before the
// law, d_i = x_i - x_{i+3} + o0. A joint whose nodes coincide then carries the traction law(o0): with o0
// from joint_initial_offset (joint_initial_state.hpp) that is the in-situ traction sigma0 n, so a joint in
// in-situ compression needs the full f_t of further tension to break, and an in-situ shear starts pre-peak.
// opening, slip and stored_energy of intact joints include o0 (stored_energy is not 0 at t = 0: book
// changes); broken joints report the geometric opening and slip, without o0.
//
// Breakage. A point has failed when its D_max reaches 1. When at least rule.fail_count points have failed
// (3 of 3, 5 of 7), the joint breaks: broken[j] is set to 1 (tensile) or 2 (shear), the joint writes zero
// force and stored energy from that call on, and an event is appended to args.breaks. The mode compares the
// sums over the joint's points of Dn^2 and Ds^2 (joint_law.hpp) at the step of breakage: tensile if the
// normal sum is at least the shear sum.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/joint_law.hpp"
#include "kernels/joint_rule.hpp"
#include "kernels/softening.hpp"

namespace rift::kernels {

enum class JointBreakMode : uint8_t { intact = 0, tensile = 1, shear = 2 };

struct JointBreak {
  int32_t joint;
  JointBreakMode mode;
  // What the joint stored at the instant it broke [J]: recoverable energy that leaves the joint's books
  // with its forces but was not dissipated by fracture (in mode II under compression, 1/2 sigma_n o of the
  // compression branch, which the contact or nothing takes over).
  double released_energy = 0.0;
};

struct JointArgs {
  std::span<const double> x;                 // current positions, 3 per node
  std::span<const int32_t> joint_nodes;      // 6 per joint: side A corners 0-2, then the facing B corners
  std::span<const int32_t> material;         // 1 per joint, index into materials
  std::span<const JointMaterial> materials;  // preconditions: p, f_t, c > 0, G_I, G_II > 0, tan(phi) >= 0
  const JointRule* rule;                     // joint_rule(3) or joint_rule(7)
  Softening softening;
  std::span<double> d_max;    // in/out, rule->points per joint: the D_max history, starts at 0
  std::span<uint8_t> broken;  // in/out, 1 per joint: a JointBreakMode value; nonzero joints are skipped
  // out, 9 per joint: x y z of the forces on the side-B corners 3, 4, 5; side-A corner i carries exactly
  // minus that of corner i + 3 (see above), so it is not stored (the node pass reads it negated).
  std::span<double> corner_force;
  // Optional outputs, 1 per joint; an empty span skips that output.
  std::span<double> opening;        // weighted mean of o over the points [m] (also for broken joints)
  std::span<double> slip;           // weighted mean of s [m] (also for broken joints)
  std::span<double> damage;         // max D_max over the points; 1 for broken joints
  std::span<double> stored_energy;  // recoverable energy, integrated over the area [J]; 0 when broken
  // Break events: appended at index break_count->fetch_add(1) when that index is < breaks.size(); later
  // ones are counted in JointStatus::breaks_dropped (find them from `broken`). Threads share the counter, so
  // the order of events is not deterministic: sort by joint before use. break_count may be null only when
  // breaks is empty.
  std::span<JointBreak> breaks;
  std::atomic<size_t>* break_count = nullptr;
  // Optional input, 3 per joint: the initial offset o0 [m] (see above); empty = none.
  std::span<const double> initial_offset = {};
  // In/out, 3 x rule->points per joint: each point's residual-friction anchor (joint_law.hpp,
  // residual_friction()), starts at 0. Empty: the materials' residual friction is not applied.
  std::span<double> residual_anchor = {};
};

struct JointStatus {
  size_t broke = 0;            // joints that broke in this call
  size_t breaks_dropped = 0;   // of which did not fit into args.breaks
  size_t degenerate = 0;       // mid-surface area zero or not finite: all outputs 0, history untouched
  size_t damage_onsets = 0;    // integration points whose damage history left 0 in this call
  size_t short_softening = 0;  // joints whose energy_exact softening length was <= 0 and was floored
                               // (joint_law.hpp): the normal one, the unconfined shear one, or the shear
                               // one at a compressed point's confinement where the law needed it
  JointStatus& operator+=(const JointStatus& o) {
    broke += o.broke;
    breaks_dropped += o.breaks_dropped;
    degenerate += o.degenerate;
    damage_onsets += o.damage_onsets;
    short_softening += o.short_softening;
    return *this;
  }
};

// Joints [begin, end). Outputs are overwritten, not accumulated; ranges may be split arbitrarily between
// threads. A joint's bits depend on the split only where its group of 4 (from begin) holds a broken or
// degenerate joint, or a damaged point with residual friction, and so goes through the scalar path, a few
// ulps apart: callers that split at fixed multiples of 4 (rift::parallel_for's blocks) get the same bits on
// any thread count. No allocation.
// Two implementations of the same law: joint_forces_scalar (one joint at a time through joint_law.hpp, the
// reference) and joint_forces (4 joints per AVX2 register; groups with a broken or degenerate joint go
// through the scalar code). Tests compare them on random joints in every state of the law.
JointStatus joint_forces_scalar(const JointArgs& args, size_t begin, size_t end);
// Fast path. Without __AVX2__ at compile time it forwards to joint_forces_scalar.
JointStatus joint_forces(const JointArgs& args, size_t begin, size_t end);
// True when joint_forces was compiled with the AVX2 path.
bool joint_forces_vectorised();

// Critical central-difference step of the intact joints in [begin, end), each on its own:
//   dt_j = 2 / omega_j,  omega_j^2 = 2 (p A / (3 h)) / min(m_0 .. m_5)   ->   dt_j = sqrt(6 h m_min / (p A))
// The law's tangent stiffness per unit area is at most p / h in every direction (compression, the start of
// both hardening curves; the secant branch has at most half of it). For the 6-node joint with that
// stiffness, integrated exactly (the 3-point rule is exact for N_i N_j), each corner's row of the stiffness
// matrix sums in absolute value to 2 p A / (3 h) per direction, so Gershgorin bounds omega^2 by that over the
// corner's lumped mass; for equal masses across the pair this is the uniform-opening mode exactly.
// Compared with femdem.md 1d's 1D estimate h sqrt(rho / p): a regular tet of edge h has corner mass
// rho h^3 / (24 sqrt 2) and face area sqrt(3) h^2 / 4, giving dt_j = 0.64 h sqrt(rho / p).
// The joint alone: a tet corner sits on 3 faces, hence in up to 3 joints, and carries its tet's stiffness
// as well. Gershgorin on the assembled system adds the omega^2 of everything at the node, so the engine
// should take dt <= alpha min(dt_tet, dt_joint / sqrt(3)) or a sharper per-node sum.
// node_mass: 1 per node [kg]. broken may be empty (all intact). Returns +infinity if no joint qualifies.
double joint_stable_step(std::span<const double> x, std::span<const int32_t> joint_nodes,
                         std::span<const int32_t> material, std::span<const JointMaterial> materials,
                         std::span<const double> node_mass, std::span<const uint8_t> broken, size_t begin,
                         size_t end);

// Each intact joint's share of the per-node Gershgorin stiffness (stable_step.hpp): 2 p A / (3 h) on each of
// its 6 nodes, the row sum above, so that K_n / m_n over the joints at a node is their omega^2 there.
// stiffness: 1 per node, added to. broken may be empty (all intact).
void add_joint_node_stiffness(std::span<const double> x, std::span<const int32_t> joint_nodes,
                              std::span<const int32_t> material, std::span<const JointMaterial> materials,
                              std::span<const uint8_t> broken, std::span<double> stiffness);

}  // namespace rift::kernels
