// The solid in a run split between the processes of a job (docs/distributed.md): each rank computes its
// share (SolidModel::compute_only), receives its ghosts' positions and velocities after each step, adds the
// step's energy sums and counts over the ranks, and sends rank 0 the rows it counts when rank 0 reads the
// store. A node counts on its owner; a tet, joint or loaded face on the owner of its first node; a break in
// the fracture log with its joint.
#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/distributed/halo_exchange.hpp"
#include "engine/distributed/log_gather.hpp"
#include "engine/distributed/share_reduction.hpp"
#include "engine/distributed/split_run.hpp"
#include "engine/distributed/store_gather.hpp"
#include "kernels/reproducible_sum.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

struct SolidSplit {
  SplitJob job;
  ShareReduction ranks;
  HaloExchange positions, velocities;
  StoreGather gather;
  std::vector<int32_t> joint_owner;
  std::vector<int32_t> owned, counted_tets, counted_joints;  // ascending
  size_t logged_at_setup = 0;                                // the fracture log's rows before the first step

  bool counts_joint(int32_t j) const { return joint_owner[size_t(j)] == job.rank; }
};

namespace {

std::vector<int32_t> rows_of(std::span<const int32_t> owner, int32_t rank) {
  std::vector<int32_t> rows;
  for (size_t r = 0; r < owner.size(); ++r)
    if (owner[r] == rank) rows.push_back(int32_t(r));
  return rows;
}

}  // namespace

void SolidSplitDelete::operator()(SolidSplit* split) const {
  delete split;
}

void SolidModel::take_share(const SplitJob& job, std::span<const SplitDomain> domains) {
  if (domains.size() != 1) throw Error("solid: a split run gives the solid one domain");
  const SplitDomain& d = domains[0];
  compute_only(d.share);  // refuses contact
  Table& nodes = store_.table(solid::node_table);
  if (d.node_owner.size() != nodes.size())
    throw Error("solid: the split's node owners do not cover the solid's nodes");
  const auto tet_owner =
      element_owners(ElementNodes{"tets", 4, solid::tet::nodes.read(store_)}, d.node_owner);
  const auto face_owner =
      element_owners(ElementNodes{"loaded faces", 3, solid::face::nodes.read(store_)}, d.node_owner);
  std::vector<int32_t> joint_owner;
  if (joint_forces_)
    joint_owner = element_owners(ElementNodes{"joints", 6, solid::joint::nodes.read(store_)}, d.node_owner);
  std::vector<RowOwners> rows{
      {solid::node_table, d.node_owner}, {solid::tet_table, tet_owner}, {solid::face_table, face_owner}};
  if (joint_forces_) rows.push_back({solid::joint_table, joint_owner});
  std::vector<int32_t> counted_joints = rows_of(joint_owner, job.rank);
  split_.reset(new SolidSplit{job, ShareReduction(job.comm), HaloExchange(job.comm, d.share, 3),
                              HaloExchange(job.comm, d.share, 3), StoreGather(job.comm, std::move(rows)),
                              std::move(joint_owner), d.share.owned, rows_of(tet_owner, job.rank),
                              std::move(counted_joints), store_.table(solid::event_table).size()});
  tet_forces_->count_only(split_->counted_tets);
  if (joint_forces_) joint_forces_->count_only(split_->counted_joints);
}

// The ghosts' positions and velocities first (the next step's forces read them), then the books in one
// process's order: the tets' damping, the node pass's sums, the joints' onsets.
void SolidModel::finish_share_step(const StepContext& ctx) {
  SolidSplit& s = *split_;
  Table& nodes = store_.table(solid::node_table);
  s.positions.begin(solid::node::x.in(nodes));
  s.velocities.begin(solid::node::v.in(nodes));
  s.positions.finish(solid::node::x.in(nodes));
  s.velocities.finish(solid::node::v.in(nodes));
  tet_forces_->book_share(ctx, s.ranks);
  integration_->book_share(s.ranks);
  if (joint_forces_) joint_forces_->book_share(s.ranks);
}

// One process's log: the breaks of set-up first, then by step, and by joint within a step.
void SolidModel::gather_to_root() {
  SolidSplit& s = *split_;
  s.gather.to_root(store_);
  if (!joint_forces_) return;
  Table& log = store_.table(solid::event_table);
  const auto joint = solid::event::joint.read(log);
  gather_log_to_root(
      s.job.comm, log, s.logged_at_setup, [&](size_t r) { return s.counts_joint(joint[r]); },
      [](const Table& t, size_t a, size_t b) {
        const auto step = solid::event::step.read(t);
        const auto joint = solid::event::joint.read(t);
        return step[a] != step[b] ? step[a] < step[b] : joint[a] < joint[b];
      });
}

double SolidModel::total_over(Rows kind, size_t rows, const std::function<double(size_t)>& term) const {
  if (!split_) return kernels::reproducible_total(rows, term);
  const SolidSplit& s = *split_;
  std::vector<int32_t> events;  // the log's rows this rank counts
  const std::vector<int32_t>* counted = &events;
  if (kind == Rows::nodes) counted = &s.owned;
  if (kind == Rows::tets) counted = &s.counted_tets;
  if (kind == Rows::joints) counted = &s.counted_joints;
  int64_t count[1] = {int64_t(rows)};
  if (kind == Rows::events) {
    const auto joint = solid::event::joint.read(store_);
    for (size_t r = 0; r < rows; ++r)
      if (s.counts_joint(joint[r])) events.push_back(int32_t(r));
    count[0] = int64_t(events.size());
    s.ranks.sum(count);  // the log's rows in one process
  }
  double largest[1] = {0.0};
  for (int32_t r : *counted) largest[0] = std::max(largest[0], std::abs(term(size_t(r))));
  s.ranks.max(largest);
  const kernels::ReproducibleGrid grid = kernels::reproducible_grid(largest[0], count[0]);
  kernels::ReproducibleSum sum[1];
  for (int32_t r : *counted) sum[0].add(term(size_t(r)), grid);
  s.ranks.sum(sum);
  return sum[0].value();
}

}  // namespace rift
