#pragma once
// The fluid in a crack is a spring across it of stiffness K_f A / w per unit area, far stiffer than the
// rock's joints once the crack is thin, and an explicit solid step that felt it through last step's
// pressure would have to shrink its stable step to it. The closure takes that spring implicitly inside
// each explicit step (docs/hydraulic-fracture.md, "Stability"):
//   1. the node pass moves the nodes with the pressure p_applied that was on the faces (predictor);
//   2. the wet faces' corner nodes would move further, by dt^2 g dp a / m, under a pressure change dp,
//      where a is the node's pressure area vector (the sum of A/3 n over its wet faces, signed so that a
//      positive pressure opens the crack) and g = 1 / (1 + c dt / 2) the mass damping's factor; a vertex's
//      volume therefore grows by C dp with C = dt^2 g sum over its nodes of |a|^2 / m;
//   3. the flow solves its step with V(p) = V_pred + C (p - p_applied) (systems/fracture_flow/network_flow);
//   4. the nodes take the correction for dp = p_new - p_applied, so positions, velocities and the crack's
//      volume all belong to the new pressure.
// A node sees the pressure of its own vertex only (the lumped load: each corner carries A/3 of its face),
// so C is diagonal: no coupled solve is needed for the closure.
#include <cstdint>
#include <span>

namespace rift::kernels {

// The wet corner nodes, listed once each (entry i is solid node node[i]).
struct CrackClosureNodes {
  std::span<const int32_t> node;        // 1 per entry: the solid node
  std::span<const int32_t> vertex;      // 1 per entry: the network vertex whose pressure acts on it
  std::span<const double> area_vector;  // 3 per entry: a [m^2]
  // 1 per entry: its node's inverse mass, and 3 per entry: 0 for a component its node has held (no
  // correction). Kept beside the entries rather than read through `node`: the solid's node arrays are
  // large and the entries scattered over them, so each indirect load would be a cache miss.
  std::span<const double> inv_mass;
  std::span<const uint8_t> free_mask;
  // 3 per entry, or empty (then area_vector): the part of a over the faces whose corner at this node is
  // open beyond the aperture floor. A floored corner's volume does not follow its nodes, so only this part
  // turns their motion into volume: C = dt^2 g sum a_open . a / m.
  std::span<const double> open_area_vector = {};
};

// The pressure area vectors of entries [begin, end) (rows of area_vector), each gathered from its faces'
// corners: corner k of side A (k < 3) of a wet triangle adds +A/3 n, its facing corner on side B (k >= 3)
// -A/3 n (n from B into A, the crack triangle's normal); open_area_vector the same over the corners whose
// opening (3 per triangle) exceeds `floor`. corners: per entry, its corners as 6 t + k in triangle order,
// from corners[corner_start[e]] to corners[corner_start[e + 1]]; normal 3 and area 1 per triangle. Each
// entry sums in triangle order, so any split of the entries into blocks gives the same bits.
void gather_area_vectors(std::span<const int32_t> corner_start, std::span<const int32_t> corners,
                         std::span<const double> normal, std::span<const double> area,
                         std::span<const double> opening, double floor, std::span<double> area_vector,
                         std::span<double> open_area_vector, size_t begin, size_t end);

// A wetted wall (a borehole): each face pushes on the rock with p A along its inward normal, A/3 on each
// corner. face_nodes: 3 per face, its solid nodes, ordered so that (x1 - x0) x (x2 - x0) points out of
// the rock; face_entries: 3 per face, the same corners' entries (rows of area_vector); x: 3 per solid
// node. Adds -(x1 - x0) x (x2 - x0) / 6 to each corner's area vector, so that a . dx is the hole's
// volume change, as with the crack faces.
void add_wall_area_vectors(std::span<const int32_t> face_nodes, std::span<const int32_t> face_entries,
                           std::span<const double> x, std::span<double> area_vector);

// One entry's share of its vertex's compliance, over dt^2 g: sum over free components of a_open . a / m.
double closure_weight(const CrackClosureNodes& nodes, size_t entry);

// C per vertex (added to `compliance`): dt^2 g sum over the vertex's entries of closure_weight.
void add_closure_compliance(const CrackClosureNodes& nodes, double dt, double damping_factor,
                            std::span<double> compliance);

// The correction for each entry's pressure change, from `felt` (what its node felt in the node pass) to
// `now`: x += dt^2 g dp a / m, v += dt g dp a / m on the free components (x, v: 3 per solid node). The
// nodes' rows are prefetched a few entries ahead (the entries are scattered over the node arrays).
// Returns the work of the pressure forces that the correction adds to the node pass's trapezoid book:
// dp a . dt (v + dv / 2) + felt a . dt dv / 2 per component (v the node pass's new velocity).
double apply_closure(const CrackClosureNodes& nodes, double dt, double damping_factor,
                     std::span<const double> felt, std::span<const double> now, std::span<double> x,
                     std::span<double> v);
// The same for the entries [begin, end) only (each entry moves its own node: blocks run in parallel).
double apply_closure_block(const CrackClosureNodes& nodes, double dt, double damping_factor,
                           std::span<const double> felt, std::span<const double> now, std::span<double> x,
                           std::span<double> v, size_t begin, size_t end);

}  // namespace rift::kernels
