#pragma once
// Joint (cohesive) forces between the tets of the fracture zone, and fracture events. Reads current
// positions, writes each joint's corner forces, damage history and state; every joint that breaks in
// the step becomes a row of solid_fracture_event (time, centroid, normal, mode, area), in joint order,
// so the log is the same on any thread count. Broken joints write zero force from then on; their two
// tets are the contact model's to handle.
#include <atomic>
#include <span>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/schedule/run_blocks.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/joint_forces.hpp"

namespace rift {

class ShareReduction;

class JointForceSystem : public System {
 public:
  JointForceSystem(Store& store, std::vector<kernels::JointMaterial> materials, int integration_points,
                   kernels::Softening softening);
  std::string name() const override { return "joint_forces"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  const std::vector<kernels::JointMaterial>& materials() const { return materials_; }
  const kernels::JointRule& rule() const { return *rule_; }
  kernels::Softening softening() const { return softening_; }
  size_t degenerate() const { return degenerate_; }  // joints with a collapsed mid-surface, last step
  size_t short_softening() const { return short_softening_; }
  // From the next step on, computes only the joints of `joints` (ascending): a process's share of a split
  // run (engine/mesh/halo_plan.hpp).
  void compute_only(std::span<const int32_t> joints);
  // A split run's share (after compute_only): from the next step on, the count of damage onsets (integration
  // points whose damage history left 0) is not added in the step but set by book_share() after the graph:
  // the count at the start of the share plus the points of the joints of `counted` (ascending: this rank's,
  // each joint counted by one rank) whose history is above 0 now, added over the ranks, less those at the
  // start. A history never returns to 0, so this is one process's count. Before the step graph is built.
  void count_only(std::vector<int32_t> counted);
  void book_share(const ShareReduction& ranks);

 private:
  void record_events(const StepContext& ctx, size_t count);

  Store& store_;
  std::vector<kernels::JointMaterial> materials_;
  const kernels::JointRule* rule_;
  kernels::Softening softening_;
  RunBlocks computed_;                        // the joints computed (all, until compute_only)
  std::vector<kernels::JointStatus> blocks_;  // one per block of computed_
  std::vector<kernels::JointBreak> breaks_;   // one slot per joint: every joint can break at most once
  std::atomic<size_t> break_count_{0};
  size_t degenerate_ = 0, short_softening_ = 0;
  bool share_ = false;
  std::vector<int32_t> counted_;
  int64_t onsets_at_share_ = 0, damaged_points_at_share_ = 0;
};

}  // namespace rift
