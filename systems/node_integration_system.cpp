#include "systems/node_integration_system.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>

#include "engine/distributed/share_reduction.hpp"
#include "engine/schedule/parallel.hpp"
#include "kernels/node_integration.hpp"
#include "kernels/reproducible_sum.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
constexpr size_t grain = 4096;  // a multiple of the sum unit
constexpr size_t kUnitTets = NodeIntegrationSystem::kSumUnitNodes / 4;
}  // namespace

NodeIntegrationSystem::NodeIntegrationSystem(Store& store, std::vector<SolidBoundarySpec> conditions,
                                             std::array<double, 3> gravity, TimeFunction mass_damping)
    : store_(store),
      conditions_(std::move(conditions)),
      gravity_(gravity),
      mass_damping_(std::move(mass_damping)),
      damped_(mass_damping_.highest() > 0.0) {
  prescribed_.assign(3 * std::max<size_t>(conditions_.size(), 1), 0.0);
  const size_t nodes = store_.table(solid::node_table).size();
  unit_results_.resize((nodes + kSumUnitNodes - 1) / kSumUnitNodes);
}

void NodeIntegrationSystem::gather(NodeForceSource source) {
  const NodeForceRouteEntry& e = route_entry(source);
  if (e.rows != NodeForceRows::node || !store_.table(e.table).has(e.column))
    throw std::logic_error(std::string("node pass: ") + e.table + "." + e.column +
                           " is not a node-row force column of the store");
  gathered_[static_cast<size_t>(source)] = true;
}

Access NodeIntegrationSystem::access() const {
  using solid::col;
  namespace node = solid::node;
  std::vector<std::string> reads{node::mass.key(), node::inv_mass.key(), node::free.key(),
                                 node::held.key(), node::slots.key(),    solid::slot.key()};
  const char* E = solid::energy_table;
  std::vector<std::string> writes{node::x.key(), node::v.key(), node::f.key()};
  for (const NodeForceRouteEntry& e : kNodeForceRoute) {
    if (!uses(e)) continue;
    reads.push_back(col(e.table, e.column));
    const std::string work = col(E, kBookWork[static_cast<size_t>(e.book)]);
    if (std::find(writes.begin(), writes.end(), work) == writes.end()) writes.push_back(work);
  }
  if (damped_) writes.push_back(solid::energy::damping.key());
  if (fused_) {
    const Access tets = fused_->fused_access();
    reads.insert(reads.end(), tets.reads.begin(), tets.reads.end());
    writes.insert(writes.end(), tets.writes.begin(), tets.writes.end());
  }
  return {reads, writes};
}

void NodeIntegrationSystem::run(const StepContext& ctx) {
  // The new velocity lives at t + dt/2, so prescribed velocities are evaluated there.
  for (size_t i = 0; i < conditions_.size(); ++i) {
    const SolidBoundarySpec& c = conditions_[i];
    const double scale =
        c.kind == SolidBoundarySpec::Kind::velocity ? c.function(ctx.time + 0.5 * ctx.dt) : 0.0;
    for (int k = 0; k < 3; ++k) prescribed_[3 * i + k] = c.direction[k] * scale;
  }
  Table& nodes = store_.table(solid::node_table);
  namespace node = solid::node;
  kernels::NodeIntegrationArgs args{
      ctx.dt,
      {gravity_[0], gravity_[1], gravity_[2]},
      node::x.in(nodes),
      node::v.in(nodes),
      ctx.observed ? node::f.in(nodes) : std::span<double>{},  // read by outputs and reactions only
      node::mass.in(nodes),
      node::inv_mass.in(nodes),
      node::free.in(nodes),
      node::held.in(nodes),
      prescribed_,
      mass_damping_(ctx.time)};
  for (const NodeForceRouteEntry& e : kNodeForceRoute)
    if (e.rows == NodeForceRows::node && uses(e))
      args.node_rows[args.node_row_count++] = {store_.table(e.table).span<const double>(e.column),
                                               e.book != NodeForceBook::external};
  // The slot sources' rows; slots per row: 4 per tet, 6 per joint (its row pairs), 3 per loaded face
  // (kernels::ForceSlots). Crack faces have no slots: their forces come as node rows.
  auto slot_rows = [&](NodeForceSource s) {
    const NodeForceRouteEntry& e = route_entry(s);
    return uses(e) ? store_.table(e.table).span<const double>(e.column) : std::span<const double>{};
  };
  const std::span<const double> rows[3] = {slot_rows(NodeForceSource::tets),
                                           slot_rows(NodeForceSource::joints),
                                           slot_rows(NodeForceSource::loaded_faces)};
  const int64_t tet_slots = static_cast<int64_t>(rows[0].size() / 3);
  const int64_t joint_slots = 2 * static_cast<int64_t>(rows[1].size() / 3);
  const int64_t face_slots = static_cast<int64_t>(rows[2].size() / 3);
  const kernels::ForceSlots slots{
      {rows[0], rows[1], rows[2]},
      {0, tet_slots, tet_slots + joint_slots, tet_slots + joint_slots + face_slots},
      node::slots.in(nodes),
      solid::slot.in(store_)};
  if (fused_)
    run_fused(args, slots, ctx);
  else
    parallel_for(nodes.size(), grain, [&](size_t begin, size_t end) {
      for (size_t first = begin; first < end; first += kSumUnitNodes)
        if (!skipped(first / kSumUnitNodes))
          unit_results_[first / kSumUnitNodes] =
              kernels::integrate_nodes(args, slots, first, std::min(end, first + kSumUnitNodes));
    });
  if (!share_) book_totals(nullptr);
}

// The units' work and damping, each added order-free (kernels/reproducible_sum.hpp: the largest term
// gives the grid, then the sum on it), and the count of non-finite nodes. In a split run (ranks given) the
// largest terms, the grid sums and the count are added over the ranks, exactly, so every rank books one
// process's bits; a unit another rank integrates holds zeros here.
void NodeIntegrationSystem::book_totals(const ShareReduction* ranks) {
  Table& energy = store_.table(solid::energy_table);
  const size_t units = unit_results_.size();
  constexpr size_t kDamping = kNodeForceBooks;  // the sums' slots: each book, then the damping
  const auto term = [&](size_t u, size_t b) {
    return b == kDamping ? unit_results_[u].damping : unit_results_[u].work[b];
  };
  double largest[kNodeForceBooks + 1] = {};
  int64_t non_finite[1] = {0};
  for (size_t u = 0; u < units; ++u) {
    for (size_t b = 0; b <= kNodeForceBooks; ++b) largest[b] = std::max(largest[b], std::abs(term(u, b)));
    non_finite[0] += static_cast<int64_t>(unit_results_[u].non_finite);
  }
  if (ranks) ranks->max(largest);
  kernels::ReproducibleSum sums[kNodeForceBooks + 1];
  for (size_t b = 0; b <= kNodeForceBooks; ++b) {
    const kernels::ReproducibleGrid grid =
        kernels::reproducible_grid(largest[b], static_cast<int64_t>(units));
    for (size_t u = 0; u < units; ++u) sums[b].add(term(u, b), grid);
  }
  if (ranks) {
    ranks->sum(sums);
    ranks->sum(non_finite);
  }
  non_finite_ = static_cast<size_t>(non_finite[0]);
  bool booked[kNodeForceBooks] = {};
  for (const NodeForceRouteEntry& e : kNodeForceRoute) {
    const size_t b = static_cast<size_t>(e.book);
    if (!uses(e) || booked[b]) continue;
    booked[b] = true;
    energy.span<double>(kBookWork[b])[0] += sums[b].value();
  }
  if (damped_) solid::energy::damping.in(energy)[0] += sums[kDamping].value();
}

void NodeIntegrationSystem::book_share(const ShareReduction& ranks) {
  book_totals(&ranks);
}

void NodeIntegrationSystem::run_fused(const kernels::NodeIntegrationArgs& args,
                                      const kernels::ForceSlots& slots, const StepContext& ctx) {
  const kernels::TetForceArgs tet_args = fused_->step_args(ctx);
  // 12 KB per thread, in a 64-byte aligned buffer: a whole number of cache lines each, no false sharing.
  constexpr size_t per_thread = 12 * kFusedTets;
  const size_t threads = static_cast<size_t>(tbb::this_task_arena::max_concurrency());
  const size_t bytes = threads * per_thread * sizeof(double);
  if (scratch_.size() < bytes) scratch_.resize(bytes);  // first step only
  parallel_for(block_first_piece_.size() - 1, 1, [&](size_t b, size_t) {
    const size_t thread = static_cast<size_t>(tbb::this_task_arena::current_thread_index());
    const std::span<double> scratch(reinterpret_cast<double*>(scratch_.data()) + thread * per_thread,
                                    per_thread);
    TetForceSystem::Tally tally;
    for (size_t p = block_first_piece_[b]; p < block_first_piece_[b + 1]; ++p) {
      const Piece& piece = pieces_[p];
      if (piece.tet_end == piece.tet_begin) {
        if (!skipped(piece.first_unit))
          unit_results_[piece.first_unit] =
              kernels::integrate_nodes(args, slots, piece.node_begin, piece.node_end);
        continue;
      }
      const size_t units = (piece.tet_end - piece.tet_begin + kUnitTets - 1) / kUnitTets;
      size_t computed = 0;
      for (size_t u = piece.first_unit; u < piece.first_unit + units; ++u) computed += !skipped(u);
      if (computed == 0) continue;
      // The run's corner forces go to scratch, and its nodes gather per tet (kernels/node_integration.hpp).
      // In a share, only the units it integrates: another rank's unit reads nodes this one does not
      // receive, and its inverted tets and largest power would enter this rank's tally.
      if (computed == units) {
        TetForceSystem::fused_forces(tet_args, piece.tet_begin, piece.tet_end, scratch, tally);
      } else {
        size_t unit = piece.first_unit;
        for (size_t first = piece.tet_begin; first < piece.tet_end; first += kUnitTets, ++unit)
          if (!skipped(unit))
            TetForceSystem::fused_forces(tet_args, first, std::min(piece.tet_end, first + kUnitTets),
                                         scratch.subspan(12 * (first - piece.tet_begin)), tally);
      }
      const kernels::PrivateTetForces tets{scratch,     piece.tet_begin, piece.node_begin, slots.source[1],
                                           face_joint_, face_corners_,   loaded_};
      size_t unit = piece.first_unit;
      for (size_t first = piece.tet_begin; first < piece.tet_end; first += kUnitTets, ++unit)
        if (!skipped(unit))
          unit_results_[unit] = kernels::integrate_private_tets(args, tets, slots, first,
                                                                std::min(piece.tet_end, first + kUnitTets));
    }
    fused_tallies_[b] = tally;
  });
  TetForceSystem::Tally total;
  for (const auto& t : fused_tallies_) total += t;  // order-free: counts, a lowest index and a largest term
  fused_->book(total);
  if (fused_->books_damping_in_step()) fused_->book_damping(ctx);
}

std::vector<int32_t> NodeIntegrationSystem::sum_units() const {
  std::vector<int32_t> first;
  first.reserve(unit_results_.size());
  if (!fused_) {
    for (size_t u = 0; u < unit_results_.size(); ++u)
      first.push_back(static_cast<int32_t>(u * kSumUnitNodes));
    return first;
  }
  for (const Piece& p : pieces_) {  // a plain piece is one unit; a run of tets one per kUnitTets
    const size_t unit = p.tet_end > p.tet_begin ? 4 * kUnitTets : p.node_end - p.node_begin;
    for (size_t n = p.node_begin; n < p.node_end; n += unit) first.push_back(static_cast<int32_t>(n));
  }
  return first;
}

void NodeIntegrationSystem::compute_only(std::span<const int32_t> owned) {
  const std::vector<int32_t> first = sum_units();
  unit_skipped_.assign(first.size(), 1);
  for (size_t u = 0; u < first.size(); ++u)
    if (std::binary_search(owned.begin(), owned.end(), first[u])) unit_skipped_[u] = 0;
  std::fill(unit_results_.begin(), unit_results_.end(), kernels::NodeStepResult{});
  share_ = true;
}

size_t NodeIntegrationSystem::fuse_tet_forces(TetForceSystem& tet_system) {
  const Table& nodes = store_.table(solid::node_table);
  const auto conn = solid::tet::nodes.read(store_);
  const std::span<const int32_t> range = solid::node::slots.in(nodes);
  const std::span<const int32_t> slot = solid::slot.in(store_);
  const size_t tet_count = conn.size() / 4;
  const int64_t tet_slots = 4 * static_cast<int64_t>(tet_count);
  // A tet qualifies when its corners are 4 nodes in a row, each of which has its own corner as its only
  // tet slot: then the run's scratch holds every tet force those nodes gather.
  auto own_nodes = [&](size_t e) {
    for (int k = 0; k < 4; ++k) {
      const int32_t n = conn[4 * e] + k;
      if (conn[4 * e + static_cast<size_t>(k)] != n) return false;
      int tet_slots_of_node = 0;
      for (int32_t i = range[2 * static_cast<size_t>(n)]; i < range[2 * static_cast<size_t>(n) + 1]; ++i)
        if (slot[static_cast<size_t>(i)] < tet_slots) {
          ++tet_slots_of_node;
          if (slot[static_cast<size_t>(i)] != static_cast<int32_t>(4 * e) + k) return false;
        }
      if (tet_slots_of_node != 1) return false;
    }
    return true;
  };
  std::vector<Piece> runs;
  for (size_t e = 0; e < tet_count; ++e) {
    if (!own_nodes(e)) continue;
    const size_t first = static_cast<size_t>(conn[4 * e]);
    Piece* last = runs.empty() ? nullptr : &runs.back();
    if (last && last->tet_end == e && last->node_end == first && e - last->tet_begin < kFusedTets) {
      last->tet_end = e + 1;
      last->node_end = first + 4;
    } else if (!last || first >= last->node_end) {  // pieces go in node order
      runs.push_back({first, first + 4, e, e + 1, 0});
    }
  }
  if (runs.empty() || !build_face_table(runs)) return 0;

  // Pieces in node order, plain ones cut at the multiples of a sum unit; blocks of about grain nodes.
  pieces_.clear();
  size_t next = 0, units = 0;
  auto add_plain = [&](size_t end) {
    while (next < end) {
      const size_t stop = std::min(end, (next / kSumUnitNodes + 1) * kSumUnitNodes);
      pieces_.push_back({next, stop, 0, 0, units++});
      next = stop;
    }
  };
  std::vector<std::pair<size_t, size_t>> handed;
  for (const Piece& r : runs) {
    add_plain(r.node_begin);
    pieces_.push_back({r.node_begin, r.node_end, r.tet_begin, r.tet_end, units});
    units += (r.tet_end - r.tet_begin + kUnitTets - 1) / kUnitTets;
    next = r.node_end;
    if (!handed.empty() && handed.back().second == r.tet_begin)
      handed.back().second = r.tet_end;
    else
      handed.emplace_back(r.tet_begin, r.tet_end);
  }
  add_plain(nodes.size());
  block_first_piece_.assign(1, 0);
  size_t in_block = 0;
  for (size_t p = 0; p < pieces_.size(); ++p) {
    const size_t count = pieces_[p].node_end - pieces_[p].node_begin;
    if (in_block > 0 && in_block + count > grain) {
      block_first_piece_.push_back(p);
      in_block = 0;
    }
    in_block += count;
  }
  block_first_piece_.push_back(pieces_.size());
  unit_results_.assign(units, {});
  fused_tallies_.assign(block_first_piece_.size() - 1, {});
  tet_system.hand_over(handed);
  fused_ = &tet_system;
  size_t fused_tets = 0;
  for (const auto& [b, e] : handed) fused_tets += e - b;
  return fused_tets;
}

// For each handed-over tet, the joint on each face and which tet corner each of its corners is
// (PrivateTetForces), and whether its nodes have loaded faces. False, and nothing fused, if some joint's
// side does not lie on one face of one such tet (not expected of a fracture zone's mesh).
bool NodeIntegrationSystem::build_face_table(const std::vector<Piece>& runs) {
  const Table& nodes = store_.table(solid::node_table);
  const auto conn = solid::tet::nodes.read(store_);
  const size_t tet_count = conn.size() / 4;
  std::vector<int32_t> node_tet(nodes.size(), -1);
  for (const Piece& r : runs)
    for (size_t e = r.tet_begin; e < r.tet_end; ++e)
      for (size_t k = 0; k < 4; ++k) node_tet[static_cast<size_t>(conn[4 * e + k])] = static_cast<int32_t>(e);
  face_joint_.assign(4 * tet_count, -1);
  face_corners_.assign(4 * tet_count, 0);
  loaded_.assign(tet_count, 0);
  if (store_.has(solid::joint_table)) {
    const auto joint_nodes = solid::joint::nodes.read(store_);
    for (size_t j = 0; j < joint_nodes.size() / 6; ++j)
      for (size_t side = 0; side < 2; ++side) {  // 0: A (takes the rows negated), 1: B
        const int32_t* n = &joint_nodes[6 * j + 3 * side];
        const int32_t e = node_tet[static_cast<size_t>(n[0])];
        if (e < 0) continue;  // a tet that stays with the slot-list pass
        int corner_sum = 0;
        unsigned corners = 0;
        for (int i = 0; i < 3; ++i) {
          const int32_t k = n[i] - conn[4 * static_cast<size_t>(e)];
          if (node_tet[static_cast<size_t>(n[i])] != e || k < 0 || k > 3) return false;
          corner_sum += k;
          corners |= static_cast<unsigned>(k) << (2 * i);
        }
        const size_t face = 4 * static_cast<size_t>(e) + static_cast<size_t>(6 - corner_sum);  // opposite
        if (corner_sum < 3 || corner_sum > 6 || face_joint_[face] >= 0) return false;
        face_joint_[face] = static_cast<int32_t>(2 * j + (side == 0 ? 1 : 0));
        face_corners_[face] = static_cast<uint8_t>(corners);
      }
  }
  // Loaded faces' slots come after the tets' (4 per tet) and the joints' (6 per joint).
  const int64_t loads_first =
      static_cast<int64_t>(conn.size()) +
      (store_.has(solid::joint_table) ? 6 * static_cast<int64_t>(store_.table(solid::joint_table).size())
                                      : 0);
  const std::span<const int32_t> range = solid::node::slots.in(nodes);
  const std::span<const int32_t> slot = solid::slot.in(store_);
  for (size_t n = 0; n < nodes.size(); ++n)
    if (node_tet[n] >= 0 && range[2 * n + 1] > range[2 * n] &&
        slot[static_cast<size_t>(range[2 * n + 1] - 1)] >= loads_first)
      loaded_[static_cast<size_t>(node_tet[n])] = 1;
  return true;
}

}  // namespace rift
