#pragma once
// Solid volume fraction on the fluid mesh (fluid.md 1.5 and 1.11: alpha_s,K = |K ∩ Omega_s| / |K| per fluid
// tet K, P0, exact and conservative), the first building block of the immersed-solid coupling.
//
// The solid Omega_s is the union of the solid tets, which do not overlap each other, so
//   |K ∩ Omega_s| = sum over solid tets S of |K ∩ S|   (tet_intersection.hpp, exact up to round-off),
// summed over the candidate pairs (K, S) of coupling_broad_phase below. Conservation follows: summed over
// all fluid tets, sum_K |K ∩ Omega_s| = |Omega_s ∩ fluid mesh|, the solid volume when the fluid mesh covers
// it (tested to 1e-10 relative on rotated meshes of different resolution). alpha = that volume / |K|,
// clamped to [0, 1]: the clamp only acts on round-off, or where solid tets overlap (they should not).
//
// Determinism. Each fluid tet's sum runs over its pairs in list order (sorted by solid tet), so its value
// does not depend on how [begin, end) ranges are split between threads: bitwise identical on any number of
// threads. Each fluid tet writes only its own outputs; no allocation.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rift::kernels {

struct CouplingPair {
  int32_t fluid, solid;  // fluid tet id, solid tet id
  friend bool operator==(const CouplingPair&, const CouplingPair&) = default;
  friend bool operator<(const CouplingPair& p, const CouplingPair& q) {
    return p.fluid < q.fluid || (p.fluid == q.fluid && p.solid < q.solid);
  }
};

struct VolumeFractionArgs {
  std::span<const double> fluid_x;           // fluid node positions, 3 per node
  std::span<const int32_t> fluid_tet_nodes;  // 4 per fluid tet
  std::span<const double> solid_x;           // solid node positions, 3 per node
  std::span<const int32_t> solid_tet_nodes;  // 4 per solid tet
  std::span<const CouplingPair> pairs;       // candidates, sorted (by fluid tet, then solid tet)
  std::span<double> solid_volume;            // out, 1 per fluid tet: |K ∩ Omega_s| [m^3]
  std::span<double> fraction;                // out, 1 per fluid tet: alpha_s in [0, 1]; 0 for a flat K
};

struct VolumeFractionStatus {
  size_t pairs = 0;         // candidate pairs evaluated
  size_t intersecting = 0;  // of which with a non-zero volume
  size_t cut = 0;           // fluid tets with 0 < alpha < 1
  VolumeFractionStatus& operator+=(const VolumeFractionStatus& o) {
    pairs += o.pairs;
    intersecting += o.intersecting;
    cut += o.cut;
    return *this;
  }
};

// Fluid tets [begin, end): outputs overwritten (tets without pairs get 0). Finds the first pair of `begin`
// by binary search, so ranges may be split arbitrarily between threads.
VolumeFractionStatus volume_fraction(const VolumeFractionArgs& args, size_t begin, size_t end);

// Candidate pairs: every (fluid tet, solid tet) whose bounding boxes, each inflated by buffer / 2 on every
// side, overlap as closed intervals on the three axes (the contact broad phase's test, bipartite). Boxes
// come from kernels::tet_bounding_boxes (contact_broad_phase.hpp), one per tet, indexed by tet id.
//
// Method. The solid boxes are binned on a uniform grid of cell size c = (largest inflated solid box edge)
// x (1 + 1e-6), each by the cell of its lower corner, and sorted by cell key (iz ny + iy) nx + ix. A solid
// box that overlaps a fluid box [lo, hi] has its lower corner in [lo - c, hi] on each axis (its edge is < c),
// so for each fluid box the cells of that range are scanned row by row (one binary search per (iy, iz)
// row, the row's x-cells being consecutive keys), each solid box there is tested, and the fluid box's hits
// are sorted by solid id. Fluid boxes are taken in id order, so the output is sorted (fluid, solid) and
// depends only on the boxes. Sequential; O(n_s log n_s + n_f (rows log n_s) + tests + pairs). The grid
// is capped at 2^20 cells per axis (c grows if the solid is wider); cells are never stored.
struct CouplingBroadPhaseArgs {
  std::span<const double> fluid_lo, fluid_hi;  // 3 per fluid tet
  std::span<const double> solid_lo, solid_hi;  // 3 per solid tet
  double buffer = 0.0;                         // b >= 0 [m]
};

// Scratch and output, reused between calls (resized, never shrunk: once large enough a call allocates
// nothing; `grows` counts the calls that had to grow a capacity).
struct CouplingBroadPhaseWorkspace {
  std::vector<uint64_t> cell_of;    // each solid box's cell key, by solid id
  std::vector<uint64_t> keys;       // the same keys, sorted
  std::vector<int32_t> order;       // solid ids in key order
  std::vector<double> sorted_box;   // 6 per solid box in key order: inflated lo xyz, hi xyz
  std::vector<int32_t> hits;        // one fluid box's solid ids
  std::vector<CouplingPair> pairs;  // the output of the last call
  size_t grows = 0;
};

struct CouplingBroadPhaseStats {
  size_t pairs = 0;      // pairs in ws.pairs
  size_t tested = 0;     // box-box tests made
  double cell_size = 0;  // c [m]
};

CouplingBroadPhaseStats coupling_broad_phase(const CouplingBroadPhaseArgs& args,
                                             CouplingBroadPhaseWorkspace& ws);

// Reference: the same pairs by testing all n_f x n_s boxes. For tests.
std::vector<CouplingPair> coupling_broad_phase_brute_force(const CouplingBroadPhaseArgs& args);

}  // namespace rift::kernels
