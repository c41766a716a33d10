#include "systems/contact_system.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "engine/mesh/tet_faces.hpp"
#include "engine/schedule/parallel.hpp"
#include "kernels/tet_geometry.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {

constexpr size_t kPairGrain = 256;
constexpr size_t kTetGrain = 2048;

using Corners = double[4][3];

void tet_corners(std::span<const double> x, std::span<const int32_t> tet_nodes, size_t t, Corners& c) {
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) c[k][i] = x[3 * tet_nodes[4 * t + k] + i];
}

double triangle_area(const double* a, const double* b, const double* c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Union-find root with path halving.
int32_t find_root(std::vector<int32_t>& parent, int32_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

ContactSystem::ContactSystem(Store& store, const ContactSpec& spec, size_t input_vertex_count,
                             std::span<const double> tet_density, std::vector<double> tet_penalty)
    : store_(store), input_vertex_count_(input_vertex_count) {
  if (!spec.penalty) tet_penalty_ = std::move(tet_penalty);
  Table& nodes = store_.table(solid::node_table);
  nodes.add<double>(node_force_column(NodeForceSource::contact), 3);
  solid::node::x_detect.create(nodes);
  if (store_.has(solid::joint_table)) solid::joint::in_contact.create(store_);
  Table& pairs = store_.add_table(solid::contact_pair_table);
  solid::contact_pair::tets.create(pairs).indexes(IndexTarget::rows_of(solid::tet_table));
  solid::contact_pair::history.create(pairs);
  solid::contact_pair::force.create(pairs);
  solid::contact_pair::friction_dissipation.create(pairs);
  solid::contact_pair::damping_dissipation.create(pairs);
  Table& energy = store_.table(solid::energy_table);
  for (const auto& c : {solid::energy::contact_work, solid::energy::friction, solid::energy::contact_damping})
    c.create(energy);
  Table& state = store_.add_table(solid::contact_state_table);
  solid::contact_state::detections.create(state);
  state.resize(1);
  is_candidate_.assign(store_.table(solid::tet_table).size(), 0);
  derive_constants(spec, tet_density);
  find_bodies_and_boundary_tets();
  estimate_stable_step();
  spdlog::info(
      "contact: penalty {:.4g} Pa, friction {:.4g}, k_t {:.4g} N/m, damping {:.4g} N s/m, buffer {:.4g} m, "
      "stable step {:.4g} s; {} bodies ({} boundary tets take part from the start)",
      law_.penalty, law_.friction, law_.tangential_stiffness, law_.normal_damping, buffer_, stable_step_,
      bodies_, bodies_ > 1 ? boundary_tets_.size() : 0);
}

ContactSystem::~ContactSystem() = default;

void ContactSystem::derive_constants(const ContactSpec& spec, std::span<const double> tet_density) {
  const Table& tets = store_.table(solid::tet_table);
  const auto x0 = solid::node::x0.read(store_);
  const auto conn = solid::tet::nodes.read(tets);
  double sum_v = 0.0, sum_a = 0.0, sum_l = 0.0, sum_m = 0.0;
  for (size_t t = 0; t < tets.size(); ++t) {
    Corners c;
    tet_corners(x0, conn, t, c);
    const double v = kernels::tet_volume(c);
    double a_sum = 0.0;
    for (const auto& f : kTetFaceCorners) a_sum += triangle_area(c[f[0]], c[f[1]], c[f[2]]);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        sum_l +=
            std::sqrt((c[i][0] - c[j][0]) * (c[i][0] - c[j][0]) + (c[i][1] - c[j][1]) * (c[i][1] - c[j][1]) +
                      (c[i][2] - c[j][2]) * (c[i][2] - c[j][2]));
    sum_v += v;
    sum_a += a_sum / 4.0;
    sum_m += tet_density[t] * v;
  }
  const double n = static_cast<double>(std::max<size_t>(tets.size(), 1));
  const double v = sum_v / n, a = sum_a / n, l = sum_l / (6.0 * n), m = sum_m / n;
  // Per-tet penalties: the pair constants (k_t, damping) and the log use their mean.
  double penalty = spec.penalty ? *spec.penalty : 0.0;
  if (!tet_penalty_.empty()) {
    for (double p : tet_penalty_) penalty += p;
    penalty /= static_cast<double>(tet_penalty_.size());
  }
  const double k_n = 8.0 * penalty * a * a / (3.0 * v);
  law_.penalty = penalty;
  law_.friction = spec.friction;
  law_.tangential_stiffness = spec.friction > 0 ? spec.tangential_penalty * law_.penalty * l : 0.0;
  law_.normal_damping = 2.0 * spec.damping * std::sqrt(k_n * 0.5 * m);
  law_.reference_stiffness = k_n;
  buffer_ = spec.buffer ? *spec.buffer : 0.1 * l;
}

// Bodies: components of the input vertices through the tets. Outer boundary faces: faces (on input
// vertices) that only one tet has. Only a mesh of several bodies needs the faces.
void ContactSystem::find_bodies_and_boundary_tets() {
  const auto vertex = solid::node::vertex.read(store_);
  const auto conn = solid::tet::nodes.read(store_);
  const size_t tets = conn.size() / 4;
  std::vector<int32_t> parent(input_vertex_count_);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<uint8_t> used(input_vertex_count_, 0);
  for (size_t t = 0; t < tets; ++t) {
    const int32_t r0 = find_root(parent, vertex[conn[4 * t]]);
    used[vertex[conn[4 * t]]] = 1;
    for (int k = 1; k < 4; ++k) {
      const int32_t v = vertex[conn[4 * t + k]];
      used[v] = 1;
      const int32_t r = find_root(parent, v);
      if (r != r0) parent[r] = find_root(parent, r0);
    }
  }
  bodies_ = 0;
  for (size_t v = 0; v < input_vertex_count_; ++v)
    bodies_ += used[v] && find_root(parent, static_cast<int32_t>(v)) == static_cast<int32_t>(v);
  // Tets outside the fracture zone (no joint) of one body share nodes: that continuum cannot touch itself
  // at the strains a tet survives, so its pairs are not contact pairs (saves most of a block's pairs).
  tet_body_.resize(tets);
  for (size_t t = 0; t < tets; ++t) tet_body_[t] = find_root(parent, vertex[conn[4 * t]]);
  in_zone_.assign(tets, 0);
  if (store_.has(solid::joint_table))
    for (int32_t t : solid::joint::tets.read(store_)) in_zone_[t] = 1;
  if (bodies_ < 2) return;
  std::unordered_map<FaceKey, int32_t, FaceKeyHash> count;
  count.reserve(2 * tets);
  auto key = [&](size_t t, int f) {
    return face_key({vertex[conn[4 * t + kTetFaceCorners[f][0]]], vertex[conn[4 * t + kTetFaceCorners[f][1]]],
                     vertex[conn[4 * t + kTetFaceCorners[f][2]]]});
  };
  for (size_t t = 0; t < tets; ++t)
    for (int f = 0; f < 4; ++f) ++count[key(t, f)];
  for (size_t t = 0; t < tets; ++t) {
    bool boundary = false;
    for (int f = 0; f < 4; ++f)
      if (count[key(t, f)] == 1) {
        boundary = true;
        boundary_faces_.push_back({static_cast<int32_t>(t), f});
      }
    if (boundary) boundary_tets_.push_back(static_cast<int32_t>(t));
  }
}

// Gershgorin on the contact springs: a face that may touch (a joint face, which may break, or an outer
// boundary face of a mesh of several bodies) pressed face to face has stiffness k_f = 8 p A^2 / (3 V)
// (header), a third of it on each corner. A node's springs add up to K; with the other side moving too,
// omega^2 <= 2 K / m, and the central difference is stable for dt <= 2 / omega = sqrt(2 m / K).
void ContactSystem::node_stiffness(std::vector<double>& joint, std::vector<double>& outer) const {
  const Table& nodes = store_.table(solid::node_table);
  const auto x0 = solid::node::x0.read(nodes);
  const auto conn = solid::tet::nodes.read(store_);
  outer.assign(nodes.size(), 0.0);
  joint.assign(nodes.size(), 0.0);
  auto add_face = [&](std::vector<double>& stiffness, int32_t t, const int32_t corner[3]) {
    Corners c;
    tet_corners(x0, conn, static_cast<size_t>(t), c);
    const double v = kernels::tet_volume(c);
    if (!(v > 0)) return;
    const double a = triangle_area(c[corner[0]], c[corner[1]], c[corner[2]]);
    const double p = tet_penalty_.empty() ? law_.penalty : tet_penalty_[static_cast<size_t>(t)];
    const double k = 8.0 * p * a * a / (3.0 * v);
    for (int i = 0; i < 3; ++i) stiffness[conn[4 * t + corner[i]]] += k / 3.0;
  };
  for (const auto& [t, f] : boundary_faces_) add_face(outer, t, kTetFaceCorners[f]);
  if (!store_.has(solid::joint_table)) return;
  const Table& joints = store_.table(solid::joint_table);
  const auto jn = solid::joint::nodes.read(joints);
  const auto jt = solid::joint::tets.read(joints);
  for (size_t j = 0; j < joints.size(); ++j)
    for (int s = 0; s < 2; ++s) {
      const int32_t t = jt[2 * j + s];
      int32_t corner[3] = {0, 1, 2};
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k)
          if (conn[4 * t + k] == jn[6 * j + 3 * s + i]) corner[i] = k;
      add_face(joint, t, corner);
    }
}

void ContactSystem::estimate_stable_step() {
  const auto mass = solid::node::mass.read(store_);
  std::vector<double> outer, joint;
  node_stiffness(joint, outer);
  auto step = [&](double k, size_t n) {
    return k > 0 && mass[n] > 0 ? std::sqrt(2.0 * mass[n] / k) : INFINITY;
  };
  stable_step_ = joint_face_stable_step_ = outer_face_stable_step_ = INFINITY;
  for (size_t n = 0; n < mass.size(); ++n) {
    stable_step_ = std::min(stable_step_, step(outer[n] + joint[n], n));
    joint_face_stable_step_ = std::min(joint_face_stable_step_, step(joint[n], n));
    outer_face_stable_step_ = std::min(outer_face_stable_step_, step(outer[n], n));
  }
}

double ContactSystem::damped_step(double dt) const {
  if (!(stable_step_ > 0) || !std::isfinite(stable_step_)) return dt;
  const double xi = damping_time() * dt / (stable_step_ * stable_step_);
  return dt * (std::sqrt(1.0 + xi * xi) - xi);
}

std::vector<double> matched_contact_penalties(const Store& store, std::span<const double> joint_penalty) {
  const auto x0 = solid::node::x0.read(store);
  const auto conn = solid::tet::nodes.read(store);
  const Table& joints = store.table(solid::joint_table);
  const auto jn = solid::joint::nodes.read(joints);
  const auto jt = solid::joint::tets.read(joints);
  const auto material = solid::joint::material.read(joints);
  std::vector<double> penalty(conn.size() / 4, INFINITY);
  for (size_t j = 0; j < joints.size(); ++j) {
    const double* p[3] = {&x0[3 * jn[6 * j]], &x0[3 * jn[6 * j + 1]], &x0[3 * jn[6 * j + 2]]};
    const double area = triangle_area(p[0], p[1], p[2]);
    double h2 = INFINITY;
    for (int i = 0; i < 3; ++i) {
      const double* a = p[i];
      const double* b = p[(i + 1) % 3];
      h2 = std::min(
          h2, (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
    }
    if (!(area > 0) || !(h2 > 0)) continue;
    const double p_j = joint_penalty[static_cast<size_t>(material[j])];
    for (int s = 0; s < 2; ++s) {
      const auto t = static_cast<size_t>(jt[2 * j + s]);
      Corners c;
      tet_corners(x0, conn, t, c);
      const double H = 3.0 * kernels::tet_volume(c) / area;
      if (H > 0) penalty[t] = std::min(penalty[t], p_j * H / (8.0 * std::sqrt(h2)));
    }
  }
  double sum = 0.0;
  size_t count = 0;
  for (double p : penalty)
    if (std::isfinite(p)) sum += p, ++count;
  const double mean = count ? sum / static_cast<double>(count) : 0.0;
  for (double& p : penalty)
    if (!std::isfinite(p)) p = mean;
  return penalty;
}

Access ContactSystem::access() const {
  using solid::col;
  const char* N = solid::node_table;
  const char* P = solid::contact_pair_table;
  std::vector<std::string> reads{solid::node::x.key(),      solid::node::v.key(),
                                 solid::node::vertex.key(), solid::tet::nodes.key(),
                                 solid::event::joint.key(), solid::event::time.key()};
  if (store_.has(solid::joint_table)) {
    reads.push_back(solid::joint::nodes.key());
    reads.push_back(solid::joint::tets.key());
    reads.push_back(solid::joint::d_max.key());
  }
  if (store_.has(solid::joint_state_table)) reads.push_back(solid::joint_state::damage_onsets.key());
  std::vector<std::string> writes{col(N, node_force_column(NodeForceSource::contact)),
                                  solid::node::x_detect.key(),
                                  solid::contact_pair::tets.key(),
                                  solid::contact_pair::history.key(),
                                  solid::contact_pair::force.key(),
                                  solid::contact_pair::friction_dissipation.key(),
                                  solid::contact_pair::damping_dissipation.key(),
                                  solid::energy::friction.key(),
                                  solid::energy::contact_damping.key(),
                                  solid::contact_state::detections.key()};
  if (store_.has(solid::joint_table)) writes.push_back(solid::joint::in_contact.key());
  // Resizes only its own pair table, which no other system touches: a declared resize, not a topology change
  // (that would serialise the whole step).
  return {reads, writes, {P}};
}

void ContactSystem::run(const StepContext& ctx) {
  const size_t events = store_.table(solid::event_table).size();
  if (events > events_seen_ || (!awake_ && bodies_ > 1)) {
    // A restored run (detections already made) replays the log to rebuild candidates and grouping only:
    // its pair list and detection positions came with the checkpoint, so detecting now would change the
    // pair table (not the physics) and the state would no longer be the straight run's bit for bit.
    const bool restored = !awake_ && solid::contact_state::detections.read(store_)[0] > 0;
    must_detect_ = (add_new_candidates() && !restored) || must_detect_;
  }
  // Damage begins at a few points on few steps: the joints are scanned only after some did (142 scans in
  // the 55,556 steps of the coarse wedge's flow sibling to 0.5 ms, 265 in hydraulic_fracture.yaml's
  // 30,286). A restored run scans once, finding nothing its checkpoint did not already hold.
  if (awake_ && store_.has(solid::joint_state_table)) {
    const int64_t onsets = solid::joint_state::damage_onsets.read(store_)[0];
    if (onsets > onsets_seen_) {
      onsets_seen_ = onsets;
      must_detect_ = add_damaged_joints() || must_detect_;
    }
  }
  if (candidates_.empty()) return;  // one intact body: nothing can touch
  if (must_detect_ || detection_needed()) detect();
  compute_forces(ctx);
}

// The first wake builds the grouping of node copies (who is still tied to whom); every break since then
// regroups the joint's three vertices and makes its two tets candidates.
bool ContactSystem::add_new_candidates() {
  const size_t before = candidates_.size(), events_before = events_seen_;
  const size_t pairs_before = joined_pairs_.size();
  const bool waking = !awake_;
  if (waking) {
    awake_ = true;
    SolidTopology topology;
    topology.input_vertex_count = input_vertex_count_;
    topology.node_vertex = solid::node::vertex.read(store_);
    topology.tet_nodes = solid::tet::nodes.read(store_);
    if (store_.has(solid::joint_table)) {
      topology.joint_nodes = solid::joint::nodes.read(store_);
      topology.joint_tets = solid::joint::tets.read(store_);
    }
    grouping_ = std::make_unique<MeshConversion>(topology);
    if (bodies_ > 1)
      for (int32_t t : boundary_tets_) add_candidate(t);
  }
  const Table& events = store_.table(solid::event_table);
  const auto joint = solid::event::joint.read(events);
  const auto time = solid::event::time.read(events);
  for (; events_seen_ < events.size(); ++events_seen_) {
    const int32_t j = joint[events_seen_];
    grouping_->break_joint(j, time[events_seen_]);
    join_joint_pair(static_cast<size_t>(j));
  }
  // A restored run: the damaged joints whose tets took part before the checkpoint take part again.
  if (waking && store_.has(solid::joint_table)) {
    const auto in_contact = solid::joint::in_contact.read(store_);
    for (size_t j = 0; j < in_contact.size(); ++j)
      if (in_contact[j]) join_joint_pair(j);
  }
  merge_joined_pairs(pairs_before);
  // New candidates need boxes; a new break also changes who is tied to whom (the exclusions).
  return candidates_.size() != before || events_seen_ != events_before;
}

// A softening joint can hinge about the line through its two compressed integration points, which do not
// see its corners: in the wedge scene a joint at the far face opened 0.47 mm at one corner while its other
// two overlapped the neighbour by 0.09-0.10 mm, a pair excluded as tied, and when the joint broke the
// contact met the whole overlap at once (25.7 kN on a 4 mm tet, 0.78 J put in within 150 steps, and the
// walls around crumbled). From its first damage the joint's two tets take part like a broken joint's.
bool ContactSystem::add_damaged_joints() {
  Table& joints = store_.table(solid::joint_table);
  // d_max, the damage history of each integration point, is current on every step (the joint's `damage`
  // only on observed ones).
  const auto d_max = solid::joint::d_max.read(joints);
  const auto in_contact = solid::joint::in_contact.read(joints);
  const size_t points = joints.size() > 0 ? d_max.size() / joints.size() : 0;
  const size_t pairs_before = joined_pairs_.size();
  for (size_t j = 0; j < joints.size(); ++j)
    if (!in_contact[j])
      for (size_t q = 0; q < points; ++q)
        if (d_max[points * j + q] > 0.0) {
          join_joint_pair(j);
          break;
        }
  if (joined_pairs_.size() == pairs_before) return false;
  merge_joined_pairs(pairs_before);
  return true;
}

void ContactSystem::add_candidate(int32_t tet) {
  if (is_candidate_[static_cast<size_t>(tet)]) return;
  is_candidate_[static_cast<size_t>(tet)] = 1;
  candidates_.push_back(tet);
}

void ContactSystem::join_joint_pair(size_t j) {
  Table& joints = store_.table(solid::joint_table);
  const auto tets = solid::joint::tets.read(joints);
  solid::joint::in_contact.in(joints)[j] = 1;
  const int32_t a = tets[2 * j], b = tets[2 * j + 1];
  add_candidate(a);
  add_candidate(b);
  joined_pairs_.push_back({std::min(a, b), std::max(a, b)});
}

// Joins are events, not steps: sorting the few new pairs into the list costs nothing per step. A joint
// that was damaged before it broke comes twice: once is kept.
void ContactSystem::merge_joined_pairs(size_t before) {
  const auto middle = joined_pairs_.begin() + static_cast<std::ptrdiff_t>(before);
  std::sort(middle, joined_pairs_.end());
  std::inplace_merge(joined_pairs_.begin(), middle, joined_pairs_.end());
  joined_pairs_.erase(std::unique(joined_pairs_.begin(), joined_pairs_.end()), joined_pairs_.end());
}

bool ContactSystem::detection_needed() {
  const auto x = solid::node::x.read(store_);
  const auto x_ref = solid::node::x_detect.read(store_);
  const auto conn = solid::tet::nodes.read(store_);
  const size_t n = candidates_.size();
  const size_t blocks = (n + kTetGrain - 1) / kTetGrain;
  auto& partial = partial_max_;
  if (partial.size() < blocks) partial.resize(blocks);
  parallel_for(n, kTetGrain, [&](size_t begin, size_t end) {
    double d2 = 0.0;
    for (size_t k = begin; k < end; ++k)
      for (int c = 0; c < 4; ++c) {
        const size_t i = 3 * static_cast<size_t>(conn[4 * candidates_[k] + c]);
        const double dx = x[i] - x_ref[i], dy = x[i + 1] - x_ref[i + 1], dz = x[i + 2] - x_ref[i + 2];
        d2 = std::max(d2, dx * dx + dy * dy + dz * dz);
      }
    partial[begin / kTetGrain] = d2;
  });
  double d2 = 0.0;
  for (size_t b = 0; b < blocks; ++b) d2 = std::max(d2, partial[b]);
  return kernels::contact_redetect_needed(std::sqrt(d2), buffer_);
}

namespace {
// The broad phase's sweep chunks on the task pool (the kernel's output does not depend on it).
void run_chunks_in_parallel(size_t count, kernels::ChunkBody body, void* context) {
  parallel_for(count, 1, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) body(context, k);
  });
}
}  // namespace

void ContactSystem::detect() {
  Table& nodes = store_.table(solid::node_table);
  const auto x = solid::node::x.read(nodes);
  const auto conn = solid::tet::nodes.read(store_);
  const size_t n = candidates_.size();
  if (lo_.size() < 3 * n) lo_.resize(3 * n), hi_.resize(3 * n);
  parallel_for(n, kTetGrain, [&](size_t begin, size_t end) {
    kernels::tet_bounding_boxes(x, conn, candidates_, lo_, hi_, begin, end);
  });
  kernels::BroadPhaseArgs args{candidates_, std::span<const double>(lo_).first(3 * n),
                               std::span<const double>(hi_).first(3 * n), buffer_};
  args.run_chunks = &run_chunks_in_parallel;
  kernels::contact_broad_phase(args, broad_);
  // Pairs still tied at some vertex, or both in one body's continuous part, are the continuum's (header).
  // Except the two tets of a damaged or broken joint: nothing else keeps their faces apart, and a pair
  // excluded while tied (elsewhere, or by its own hinging joint) sinks into itself unresisted, then meets
  // the contact with the whole overlap at once when its last tie breaks (docs/contact.md, "Never
  // excluded").
  const auto group = grouping_->node_vertex();
  auto tied = [&](const kernels::ContactPair& p) {
    if (std::binary_search(joined_pairs_.begin(), joined_pairs_.end(), p)) return false;
    if (tet_body_[p.a] == tet_body_[p.b] && !in_zone_[p.a] && !in_zone_[p.b]) return true;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (group[conn[4 * p.a + i]] == group[conn[4 * p.b + j]]) return true;
    return false;
  };
  auto& found = broad_.pairs;
  found.erase(std::remove_if(found.begin(), found.end(), tied), found.end());

  Table& table = store_.table(solid::contact_pair_table);
  const size_t old_count = table.size();
  const auto* old = reinterpret_cast<const kernels::ContactPair*>(solid::contact_pair::tets.in(table).data());
  old_pairs_.assign(old, old + old_count);
  const auto old_history = solid::contact_pair::history.in(table);
  old_history_.assign(old_history.begin(), old_history.end());
  // Nodes the old list gathered into are cleared here; compute_forces clears those of the new list.
  clear_gathered_nodes(old_pairs_);
  table.resize(found.size());
  auto* pairs = reinterpret_cast<kernels::ContactPair*>(solid::contact_pair::tets.in(table).data());
  std::copy(found.begin(), found.end(), pairs);
  kernels::remap_pair_history(old_pairs_, old_history_, {pairs, found.size()},
                              solid::contact_pair::history.in(table));
  std::copy(x.begin(), x.end(), solid::node::x_detect.in(nodes).begin());
  ++solid::contact_state::detections.in(store_)[0];
  must_detect_ = false;
}

// Zeroes solid_node.contact_force at the corners of the pairs' tets: what a gather over them wrote.
void ContactSystem::clear_gathered_nodes(std::span<const kernels::ContactPair> pairs) {
  const auto conn = solid::tet::nodes.read(store_);
  auto contact_force =
      store_.table(solid::node_table).span<double>(node_force_column(NodeForceSource::contact));
  for (const auto& p : pairs)
    for (int32_t t : {p.a, p.b})
      for (int c = 0; c < 4; ++c)
        for (int i = 0; i < 3; ++i) contact_force[3 * conn[4 * t + c] + i] = 0.0;
}

void ContactSystem::compute_forces(const StepContext& ctx) {
  Table& nodes = store_.table(solid::node_table);
  Table& table = store_.table(solid::contact_pair_table);
  const auto conn = solid::tet::nodes.read(store_);
  const std::span<const kernels::ContactPair> pairs(
      reinterpret_cast<const kernels::ContactPair*>(solid::contact_pair::tets.in(table).data()),
      table.size());
  kernels::ContactArgs args;
  args.x = solid::node::x.read(nodes);
  args.v = solid::node::v.read(nodes);
  args.tet_nodes = conn;
  args.pairs = pairs;
  args.law = law_;
  args.tet_penalty = tet_penalty_;
  args.dt = ctx.dt;
  args.history = solid::contact_pair::history.in(table);
  args.pair_force = solid::contact_pair::force.in(table);
  args.friction_dissipation = solid::contact_pair::friction_dissipation.in(table);
  args.damping_dissipation = solid::contact_pair::damping_dissipation.in(table);
  const size_t blocks = (pairs.size() + kPairGrain - 1) / kPairGrain;
  if (partial_status_.size() < blocks) partial_status_.resize(blocks);
  parallel_for(pairs.size(), kPairGrain, [&](size_t begin, size_t end) {
    partial_status_[begin / kPairGrain] = kernels::contact_forces(args, begin, end);
  });
  status_ = {};
  for (size_t b = 0; b < blocks; ++b) status_ += partial_status_[b];
  // Clear the nodes this list gathers into, then gather in pair order (deterministic).
  clear_gathered_nodes(pairs);
  kernels::contact_gather(pairs, conn, args.pair_force,
                          nodes.span<double>(node_force_column(NodeForceSource::contact)));
  double friction = 0.0, damping = 0.0;
  for (size_t k = 0; k < pairs.size(); ++k) {
    friction += args.friction_dissipation[k];
    damping += args.damping_dissipation[k];
  }
  Table& energy = store_.table(solid::energy_table);
  solid::energy::friction.in(energy)[0] += friction;
  solid::energy::contact_damping.in(energy)[0] += damping;
}

ContactTotals ContactSystem::totals() const {
  const Table& table = store_.table(solid::contact_pair_table);
  ContactTotals t;
  t.candidates = candidates_.size();
  t.pairs = table.size();
  t.touching = status_.touching;
  t.sliding = status_.sliding;
  t.detections = solid::contact_state::detections.read(store_)[0];
  return t;
}

}  // namespace rift
