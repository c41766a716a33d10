#pragma once
// Contact broad phase: which pairs of candidate tets have overlapping buffered bounding boxes
// (femdem.md 1c "Broad phase": Munjiza's NBS binning, here with a linear radix sort instead of linked lists).
//
// Input: n boxes, one per candidate tet (ids[k] its tet id; lo / hi its axis-aligned box, 3 doubles each),
// and a buffer b >= 0. Each box is inflated by h = b / 2 on every side:  lo' = lo - h,  hi' = hi + h.
// Two boxes form a candidate pair when their inflated boxes overlap as closed intervals in x, y and z:
//   lo'_A <= hi'_B  and  lo'_B <= hi'_A   (each axis)   <=>   the gap between the original boxes is <= b.
//
// Binning. Cell size c = (largest inflated box edge over all boxes and axes) x (1 + 1e-6); every box goes
// to the cell holding its lo' corner. Two overlapping boxes have |lo'_A - lo'_B| <= max edge < c on each
// axis, so their cells differ by at most 1 per axis: only the 3 x 3 x 3 neighbourhood needs testing. The
// 1e-6 margin keeps floor() on the right side of a cell boundary despite round-off (the cell coordinate has
// an absolute error ~2^-32 cells at most). Cell keys (iz Ny + iy) Nx + ix with one empty cell of padding on
// every side (no wrap-around between rows) are sorted by an LSD radix sort (11-bit digits, stable, passes
// whose digit is the same for every key skipped): O(n) for a bounded number of cells per box. The sorted
// boxes are then swept once, cell by cell; for each cell the 13 lexicographically later neighbour cells
// lie in 5 runs of consecutive keys ([k+1], [k+Nx-1, k+Nx+1], [k+NxNy+dNx-1, k+NxNy+dNx+1], d = -1, 0, 1),
// found by 5 cursors that only move forward ("no binary search", as NBS), and each unordered pair of cells
// is visited exactly once. With the grid capped at 2^20 cells per axis (c grows if the cloud is wider) a
// key fits in 63 bits; the cells themselves are never stored, so memory is O(n + pairs) whatever the span.
// The pairs found are sorted in the ranks of their ids (ids radix-sorted once): a counting sort on the
// first member (n buckets) and a short sort of each member's partners: O(n + pairs) while the partners
// per box stay bounded.
//
// Output: every pair (a, b) of tet ids with a < b whose boxes overlap, minus the pairs in `excluded`
// (same form, sorted lexicographically; e.g. tets sharing a node or tied by an intact joint), sorted
// lexicographically, each once. The result depends only on the set of (id, box) records, not on their order
// in the input nor on any thread count (the kernel is sequential; see contact_potential.hpp for the
// parallel narrow phase). Preconditions: ids >= 0 (a repeated id is taken as one tet: its pairs are merged
// and it is never paired with itself); boxes finite with lo <= hi.
//
// Cost. O(n + candidate tests + pairs). The cell size follows the largest element, so a cloud with a few
// large elements among many small ones puts many small ones in one cell (quadratic within the cell):
// OpenFDEM's answer is several size groups (femdem.md 1c); not done here.
//
// Re-detection criterion. A pair not reported had a gap g > b between its boxes at detection. If no node
// has moved by more than d since then, every box still lies inside its detection box grown by d on each
// side, so the gap is now >= g - 2d > b - 2d: the two elements can only touch (gap <= 0) once 2d > b.
// Hence detection must be re-run as soon as  d > b / 2, where d bounds every node's displacement since the
// last detection: either max_i |x_i - x_i(detection)| (max_node_displacement below; sharp) or Y's running
// sum of v_max dt over the steps since the detection (an upper bound of the same; femdem.md 1c quotes Y's
// test as sum(2 v_max dt) > buffer, the same criterion). Pairs found at the last detection stay in the list
// until the next one (the narrow phase returns zero force for those that do not overlap).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rift::kernels {

struct ContactPair {
  int32_t a, b;  // tet ids, a < b
  friend bool operator==(const ContactPair&, const ContactPair&) = default;
  friend bool operator<(const ContactPair& p, const ContactPair& q) {
    return p.a < q.a || (p.a == q.a && p.b < q.b);
  }
};

// Runs body(context, k) for every k in [0, count), in any order and possibly concurrently (the caller's
// thread pool; the kernel itself knows no threads). A plain function pointer, so a call allocates nothing.
using ChunkBody = void (*)(void* context, size_t k);
using ChunkRunner = void (*)(size_t count, ChunkBody body, void* context);

struct BroadPhaseArgs {
  std::span<const int32_t> ids;                // n: the tet id of each box
  std::span<const double> lo;                  // 3n: box minimum corner
  std::span<const double> hi;                  // 3n: box maximum corner
  double buffer = 0.0;                         // b >= 0 [m]
  std::span<const ContactPair> excluded = {};  // sorted, a < b: removed from the output
  // The sweep is cut into chunks of whole cells (a fixed count of boxes each), each with its own cursors
  // and pair buffer; with a runner they run concurrently. The pairs are sorted afterwards, so the output
  // is the same with or without a runner, on any thread count.
  ChunkRunner run_chunks = nullptr;
};

// Scratch and output, reused between calls: vectors are resized, never shrunk, so once the capacities
// cover the largest n and pair count seen, a call allocates nothing. `grows` counts the calls that had to
// grow some capacity (tests check it stays put in steady state).
struct BroadPhaseWorkspace {
  struct Entry {
    uint64_t key;  // cell key
    int32_t box;   // index into the input boxes
  };
  std::vector<Entry> entries, entries_tmp;        // boxes by cell key
  std::vector<Entry> id_entries;                  // boxes by id
  std::vector<double> sorted_box;                 // 6 per entry in cell order: lo'xyz hi'xyz
  std::vector<uint32_t> sorted_rank;              // id rank per entry in cell order
  std::vector<uint32_t> rank_of_box;              // id rank per input box
  std::vector<int32_t> rank_id;                   // the id of each rank
  std::vector<uint64_t> keys, keys_tmp;           // pair keys rank_a << 32 | rank_b
  std::vector<size_t> count;                      // radix histograms, pair-sort offsets
  std::vector<ContactPair> pairs;                 // the output of the last call
  std::vector<std::vector<uint64_t>> chunk_keys;  // pair keys found by each sweep chunk
  std::vector<size_t> chunk_begin, chunk_tested;  // first entry of each chunk (+ end), tests per chunk
  size_t grows = 0;
};

struct BroadPhaseStats {
  size_t pairs = 0;      // pairs in ws.pairs
  size_t tested = 0;     // box-box overlap tests made
  size_t excluded = 0;   // overlapping pairs removed because they were in args.excluded
  size_t cells = 0;      // occupied cells
  double cell_size = 0;  // c [m]
};

// The pairs described above, into ws.pairs. Sequential but for the sweep (args.run_chunks).
BroadPhaseStats contact_broad_phase(const BroadPhaseArgs& args, BroadPhaseWorkspace& ws);

// Reference: the same pair set (same inflation, same closed test, same exclusion and order) by testing all
// n (n - 1) / 2 pairs. For tests and benchmarks.
std::vector<ContactPair> contact_broad_phase_brute_force(const BroadPhaseArgs& args);

// Boxes of tets: for k in [begin, end), the box of tet ids[k] (corners tet_nodes[4 id .. 4 id + 3] in x,
// 3 per node) into lo[3k..3k+2], hi[3k..3k+2].
void tet_bounding_boxes(std::span<const double> x, std::span<const int32_t> tet_nodes,
                        std::span<const int32_t> ids, std::span<double> lo, std::span<double> hi,
                        size_t begin, size_t end);

// max over nodes i in [begin, end) of |x_i - x_ref_i| (3 per node): the d of the re-detection criterion when
// x_ref holds the positions at the last detection.
double max_node_displacement(std::span<const double> x, std::span<const double> x_ref, size_t begin,
                             size_t end);

// True when the pair list of the last detection may miss a touching pair: 2 d > b (see above).
inline bool contact_redetect_needed(double max_displacement, double buffer) {
  return 2.0 * max_displacement > buffer;
}

}  // namespace rift::kernels
