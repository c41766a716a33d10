#pragma once
// The node pass: gathers every force on the solid's nodes by the one route of systems/node_force_route.hpp,
// in its order, then advances velocities and positions by central difference, holding constrained
// components at their prescribed velocity, and books each source's work over the step in the
// solid_energy column the route names.
#include <vector>

#include "engine/core/aligned_buffer.hpp"
#include "engine/core/table.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/node_integration.hpp"
#include "systems/node_force_route.hpp"
#include "systems/tet_force_system.hpp"

namespace rift {

class ShareReduction;

class NodeIntegrationSystem : public System {
 public:
  // velocity_conditions[i] drives nodes whose `held` column is i (fixed supports are velocity 0).
  // mass_damping: solid.mass_damping [1/s], evaluated at the start of each step (0: none).
  NodeIntegrationSystem(Store& store, std::vector<SolidBoundarySpec> velocity_conditions,
                        std::array<double, 3> gravity, TimeFunction mass_damping = {});
  std::string name() const override { return "node_integration"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  size_t non_finite_nodes() const { return non_finite_; }
  // Gathers a source whose rows are per node (NodeForceRows::node) from now on; its column must exist.
  // The slot sources are always gathered. Before the step graph is built.
  void gather(NodeForceSource source);
  // Computes the forces of the tets whose nodes are their own inside this pass, in runs of up to
  // kFusedTets tets, each right before its nodes are integrated (TetForceSystem says why). Tets that
  // share nodes stay with the tet system. The same physics as without, rounded differently: a node's
  // joint forces and the energy sums are added in another order. Before the step graph is built. Returns
  // how many tets were handed over.
  size_t fuse_tet_forces(TetForceSystem& tets);
  static constexpr size_t kFusedTets = 128;  // 12 KB of corner forces: stays in L1 until the nodes read it
  // The energy sums' unit: up to 64 nodes (16 of a fused run's tets) whose work terms are added in a row,
  // in node order; the units' sums are then added order-free (kernels/reproducible_sum.hpp), so a split
  // of the units between threads or processes books the same bits. Units are cut from the mesh alone.
  static constexpr size_t kSumUnitNodes = 64;
  // The first node of each sum unit, ascending from 0: a split between processes keeps units whole
  // (PartitionWork::node_units).
  std::vector<int32_t> sum_units() const;
  // From the next step on, integrates only the sum units whose first node is in `owned` (ascending): a
  // process's share of a split run, whose nodes come in whole units (PartitionWork::node_units). The others
  // keep their state and book nothing. After fuse_tet_forces.
  void compute_only(std::span<const int32_t> owned);
  // A split run's share (after compute_only): from the next step on, run() leaves the units' work and
  // damping (and the fused tets' damping) unbooked; book_share() books them after the graph, each sum on
  // the grid of every rank's largest unit term, added exactly over the ranks, so the books have one
  // process's bits; and the non-finite nodes over the ranks.
  void book_share(const ShareReduction& ranks);
  // The last step's sums of each unit (each book's work, the damping), in unit order; in a share, zeros
  // for the units of other processes. What a split run adds over its ranks, order-free.
  std::span<const kernels::NodeStepResult> unit_sums() const { return unit_results_; }

 private:
  Store& store_;
  std::vector<SolidBoundarySpec> conditions_;
  std::array<double, 3> gravity_;
  TimeFunction mass_damping_;
  bool share_ = false;              // book_share books the step's sums
  bool damped_ = false;             // the damping is positive at some time: its dissipation is booked
  std::vector<double> prescribed_;  // 3 per condition, evaluated each step
  std::vector<kernels::NodeStepResult> unit_results_;  // one per sum unit, in node order
  std::vector<uint8_t> unit_skipped_;                  // per sum unit: another process integrates it
  bool skipped(size_t unit) const { return !unit_skipped_.empty() && unit_skipped_[unit] != 0; }
  size_t non_finite_ = 0;
  bool gathered_[std::size(kNodeForceRoute)] = {};  // per route entry: its node rows are gathered
  // Slot sources are gathered when their table exists, node rows when asked to (gather()).
  bool uses(const NodeForceRouteEntry& e) const {
    return e.rows == NodeForceRows::slots ? store_.has(e.table) : gathered_[static_cast<size_t>(e.source)];
  }

  // With fused tets (fuse_tet_forces): the nodes cut into pieces, each either plain nodes (one sum unit) or
  // the nodes of a run of tets [tet_begin, tet_end) (a unit per kSumUnitNodes / 4 tets); pieces grouped into
  // blocks of about `grain` nodes, in node order.
  struct Piece {
    size_t node_begin, node_end, tet_begin, tet_end;  // tet_begin == tet_end: no tets
    size_t first_unit;
  };
  void book_totals(const ShareReduction* ranks);
  void run_fused(const kernels::NodeIntegrationArgs& args, const kernels::ForceSlots& slots,
                 const StepContext& ctx);
  bool build_face_table(const std::vector<Piece>& runs);
  TetForceSystem* fused_ = nullptr;
  std::vector<Piece> pieces_;
  std::vector<size_t> block_first_piece_;             // block b covers pieces [first[b], first[b + 1])
  std::vector<TetForceSystem::Tally> fused_tallies_;  // one per block
  std::vector<int32_t> face_joint_;                   // kernels::PrivateTetForces, 4 per tet
  std::vector<uint8_t> face_corners_;                 // 4 per tet
  std::vector<uint8_t> loaded_;                       // 1 per tet
  AlignedBuffer scratch_;  // 12 kFusedTets doubles per thread of the arena, sized on the first step
};

}  // namespace rift
