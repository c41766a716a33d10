#pragma once
// Internal forces of the tetrahedra (compressible neo-Hookean + viscous damping + in-situ stress,
// kernels/tet_forces). Reads node positions and velocities, writes each tet's corner forces, stress,
// elastic energy and viscous power, and books the damping dissipation of the step in solid_energy: the
// tets' viscous powers added order-free (kernels/reproducible_sum.hpp), so that any split of the tets
// between threads or processes books the same bits.
//
// Tets with nodes of their own (a fracture zone's, numbered 4 in a row) may be handed over to the node
// pass (NodeIntegrationSystem::fuse_tet_forces): it computes their forces with fused_forces() right before
// it integrates their nodes, into a scratch block that stays in cache, so the corner forces of those tets
// never go to memory and their nodes are read once per step instead of twice. run() then computes only
// the other tets. A tet's forces are the same bits either way (kernels/tet_forces.hpp).
#include <vector>

#include "engine/core/table.hpp"
#include "engine/schedule/run_blocks.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/reproducible_sum.hpp"
#include "kernels/tet_forces.hpp"

namespace rift {

class ShareReduction;

class TetForceSystem : public System {
 public:
  // initial_stress: 6 per material (empty: none).
  TetForceSystem(Store& store, std::vector<kernels::TetMaterial> materials,
                 std::vector<double> initial_stress);
  std::string name() const override { return "tet_forces"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  // Inverted tets (J <= 0) seen in the last step, and the lowest index among them.
  size_t inverted() const { return inverted_; }
  int64_t first_inverted() const { return first_inverted_; }

  // What the tet pass books besides the forces: inverted tets and the largest viscous power [W] (the grid
  // of the order-free sum of the powers).
  struct Tally {
    kernels::TetForceStatus status;
    double largest_viscous_power = 0.0;
    Tally& operator+=(const Tally& o);  // in any order: counts, a lowest index and a maximum
  };
  // From the next step on, run() skips tets [begin, end) of each range (sorted, disjoint); the node pass
  // computes them. Before the step graph is built.
  void hand_over(const std::vector<std::pair<size_t, size_t>>& ranges);
  // The kernel's arguments for this step, corner forces to the corner_force column; for the node pass, once
  // per step (it then points corner_force at its scratch).
  kernels::TetForceArgs step_args(const StepContext& ctx) const;
  // Handed-over tets [begin, end), for the node pass: corner forces into scratch (12 per tet, tet `begin`
  // first), stress and energy (when observed) and viscous power into their columns; adds to tally.
  static void fused_forces(kernels::TetForceArgs a, size_t begin, size_t end, std::span<double> scratch,
                           Tally& tally);
  // Books a tally into this step's inverted count: run()'s own, then the node pass's for the handed-over
  // tets (after run()). Then, once every tet's power of the step is in its column, book_damping() adds
  // dt times their sum to the damping: run() calls it when no tets are handed over, else the node pass.
  void book(const Tally& tally);
  void book_damping(const StepContext& ctx);
  // The tets' columns the node pass reads and writes when it computes handed-over tets.
  Access fused_access() const;
  // From the next step on, run() computes only the tets of `tets` (ascending) that it has not handed over:
  // a process's share of a split run (engine/mesh/halo_plan.hpp). After hand_over.
  void compute_only(std::span<const int32_t> tets);
  // A split run's share: from the next step on, the damping is not booked in the step (run() and the node
  // pass leave it), but by book_share() after the graph, over the tets of `counted` (ascending: those this
  // rank counts, each tet counted by one rank), on the grid of every rank's largest power, added exactly
  // over the ranks; the inverted tets are added over the ranks too. Before the step graph is built.
  void count_only(std::vector<int32_t> counted);
  bool books_damping_in_step() const { return !share_; }
  void book_share(const StepContext& ctx, const ShareReduction& ranks);

 private:
  Store& store_;
  std::vector<kernels::TetMaterial> materials_;
  std::vector<double> initial_stress_;
  // The tets run() computes (all, until hand_over), in runs cut at the multiples of `grain`, blocks of a
  // grain-aligned stretch each, so a zone that leaves many short runs does not make as many tasks. One
  // tally per block.
  RunBlocks own_;
  std::vector<Tally> tallies_;
  std::vector<kernels::ReproducibleSum> damping_parts_;  // one per block of the damping's sum
  bool handed_over_ = false;
  size_t inverted_ = 0;
  int64_t first_inverted_ = -1;
  double largest_viscous_power_ = 0.0;  // this step's
  void book_damping_power(double dt, double power);
  bool share_ = false;  // count_only: a split run's share
  std::vector<int32_t> counted_;
};

}  // namespace rift
