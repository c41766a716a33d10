// The node pass (kernels/node_integration.hpp): gathered forces, central difference, held components and
// the work of each source, against a direct evaluation, on random slot lists; and the same bits whatever
// the split of the node range (the kernel prefetches ahead inside its range and must not read past it).
// The per-tet gather of the fused tet pass (integrate_private_tets) against the per-node one, on private
// nodes with random joints and loaded faces.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernels/node_integration.hpp"

namespace rift::kernels {
namespace {

// Random nodes with 1 tet slot, 0-3 joint slots and 0-1 face slots each (grouped by source, as set-up
// builds them; joint slots are pairs over rows of joint_force, ForceSlots), random forces, masses, and a few
// held components (fixed or driven).
struct Problem {
  size_t nodes = 0;
  std::vector<double> tet_force, joint_force, face_force;
  int64_t first_slot[4] = {};
  std::vector<int32_t> node_range, slots;
  std::vector<double> x, v, f, mass, inv_mass, prescribed;
  std::vector<uint8_t> free_mask;
  std::vector<int32_t> held;

  Problem() = default;
  explicit Problem(size_t n) : nodes(n) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> joints_per_node(0, 3), faces_per_node(0, 1);
    const size_t tet_slots = n, joint_slots = 2 * n, face_slots = n / 2;
    for (auto* column : {&tet_force, &joint_force, &face_force}) column->clear();
    for (size_t k = 0; k < 3 * tet_slots; ++k) tet_force.push_back(1e3 * unit(rng));
    for (size_t k = 0; k < 3 * joint_slots; ++k) joint_force.push_back(1e3 * unit(rng));
    for (size_t k = 0; k < 3 * face_slots; ++k) face_force.push_back(1e2 * unit(rng));
    first_slot[1] = static_cast<int64_t>(tet_slots);
    first_slot[2] = first_slot[1] + static_cast<int64_t>(joint_slots);
    first_slot[3] = first_slot[2] + static_cast<int64_t>(face_slots);
    std::uniform_int_distribution<int64_t> joint(0, static_cast<int64_t>(joint_slots) - 1),
        face(0, static_cast<int64_t>(face_slots) - 1);
    for (size_t i = 0; i < n; ++i) {
      node_range.push_back(static_cast<int32_t>(slots.size()));
      slots.push_back(static_cast<int32_t>(i));  // its tet corner
      for (int j = joints_per_node(rng); j > 0; --j)
        slots.push_back(static_cast<int32_t>(first_slot[1] + joint(rng)));
      for (int j = faces_per_node(rng); j > 0; --j)
        slots.push_back(static_cast<int32_t>(first_slot[2] + face(rng)));
      node_range.push_back(static_cast<int32_t>(slots.size()));
    }
    for (size_t k = 0; k < 3 * n; ++k) {
      x.push_back(unit(rng));
      v.push_back(0.1 * unit(rng));
      free_mask.push_back(k % 17 == 0 ? 0 : 1);
      held.push_back(k % 34 == 0 ? 0 : -1);  // half of the held components are driven by condition 0
    }
    f.assign(3 * n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      mass.push_back(1e-3 * (1.5 + unit(rng)));
      inv_mass.push_back(i % 50 == 0 ? 0.0 : 1.0 / mass.back());  // some massless nodes
    }
    prescribed = {0.25, -0.5, 0.125};
  }

  NodeIntegrationArgs args() {
    return {1e-6, {0.0, 0.0, -9.81}, x, v, f, mass, inv_mass, free_mask, held, prescribed};
  }
  ForceSlots force_slots() const {
    return {{tet_force, joint_force, face_force},
            {first_slot[0], first_slot[1], first_slot[2], first_slot[3]},
            node_range,
            slots};
  }
  // Component c of the force in a slot; joint slots come in pairs (ForceSlots): 2 r reads row r, 2 r + 1
  // its negative.
  double slot_force(int32_t slot, int c) const {
    if (slot < first_slot[1]) return tet_force[3 * static_cast<size_t>(slot) + c];
    if (slot < first_slot[2]) {
      const auto e = static_cast<size_t>(slot - first_slot[1]);
      return (e % 2 ? -1.0 : 1.0) * joint_force[3 * (e / 2) + c];
    }
    return face_force[3 * static_cast<size_t>(slot - first_slot[2]) + c];
  }
};

TEST(NodeIntegration, MatchesDirectEvaluation) {
  Problem p(2000);
  const std::vector<double> x0 = p.x, v0 = p.v;
  const NodeIntegrationArgs a = p.args();
  const NodeStepResult r = integrate_nodes(a, p.force_slots(), 0, p.nodes);
  EXPECT_EQ(r.non_finite, 0u);
  double work[3] = {0.0, 0.0, 0.0};
  for (size_t n = 0; n < p.nodes; ++n)
    for (int c = 0; c < 3; ++c) {
      double by_source[3] = {0.0, 0.0, 0.0};
      for (int32_t k = p.node_range[2 * n]; k < p.node_range[2 * n + 1]; ++k) {
        const int32_t slot = p.slots[k];
        const int src = (slot >= p.first_slot[1]) + (slot >= p.first_slot[2]);
        by_source[src] += p.slot_force(slot, c);
      }
      const size_t i = 3 * n + c;
      const double total = by_source[0] + by_source[1] + by_source[2];
      const double held = p.held[i] >= 0 ? p.prescribed[c] : 0.0;
      const double vn = p.free_mask[i] ? v0[i] + a.dt * (total * p.inv_mass[n] + a.gravity[c]) : held;
      const double tol = 1e-12 * (1.0 + std::abs(vn));
      EXPECT_NEAR(p.f[i], total, 1e-12 * (1.0 + std::abs(total)));
      EXPECT_NEAR(p.v[i], vn, tol);
      EXPECT_NEAR(p.x[i], x0[i] + a.dt * vn, 1e-15);
      const double dx = 0.5 * a.dt * (v0[i] + vn);
      work[0] += by_source[0] * dx;
      work[1] += by_source[1] * dx;
      work[2] += p.free_mask[i]
                     ? (by_source[2] + p.mass[n] * a.gravity[c]) * dx
                     : 0.5 * p.mass[n] * (vn * vn - v0[i] * v0[i]) - (by_source[0] + by_source[1]) * dx;
    }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.work[k], work[k], 1e-12 * (1e-9 + std::abs(work[k]))) << k;
  EXPECT_EQ(r.work[3], 0.0);  // no contact column
}

// Blocks of any size give the same bits (the prefetch near a block's end stays inside it).
TEST(NodeIntegration, SameBitsForAnySplit) {
  Problem whole(3001), split(3001);
  const NodeStepResult r = integrate_nodes(whole.args(), whole.force_slots(), 0, whole.nodes);
  NodeStepResult sum;
  const NodeIntegrationArgs a = split.args();
  const ForceSlots s = split.force_slots();
  for (size_t begin = 0, size = 1; begin < split.nodes; begin += size, size = size * 3 + 1)
    sum += integrate_nodes(a, s, begin, std::min(split.nodes, begin + size));
  EXPECT_EQ(whole.x, split.x);
  EXPECT_EQ(whole.v, split.v);
  EXPECT_EQ(whole.f, split.f);
  EXPECT_EQ(r.non_finite, sum.non_finite);
}

// Node rows (forces a producer gathered per node) join after the slots, in array order: external rows
// add to the loaded faces' sum in that order, internal rows (contact) make a fourth internal source whose
// work is work[3]. The same step with the node rows' sums folded into extra slots of the same sources
// would round differently, so the reference is the documented order itself, compared bit for bit.
TEST(NodeIntegration, NodeRowsJoinInArrayOrder) {
  Problem with_rows(500), reference(500);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> fluid(3 * with_rows.nodes), crack(3 * with_rows.nodes), contact(3 * with_rows.nodes);
  for (auto* rows : {&fluid, &crack, &contact})
    for (double& value : *rows) value = unit(rng);
  NodeIntegrationArgs a = with_rows.args();
  a.node_rows[a.node_row_count++] = {fluid, false};
  a.node_rows[a.node_row_count++] = {crack, false};
  a.node_rows[a.node_row_count++] = {contact, true};
  const NodeStepResult r = integrate_nodes(a, with_rows.force_slots(), 0, with_rows.nodes);

  const NodeIntegrationArgs b = reference.args();
  const std::vector<double> v0 = reference.v;
  double work3 = 0.0;
  for (size_t n = 0; n < reference.nodes; ++n)
    for (int c = 0; c < 3; ++c) {
      double by_source[3] = {0.0, 0.0, 0.0};
      for (int32_t k = reference.node_range[2 * n]; k < reference.node_range[2 * n + 1]; ++k) {
        const int32_t slot = reference.slots[k];
        by_source[(slot >= reference.first_slot[1]) + (slot >= reference.first_slot[2])] +=
            reference.slot_force(slot, c);
      }
      const size_t i = 3 * n + c;
      const double external = (by_source[2] + fluid[i]) + crack[i];
      const double total = (by_source[0] + by_source[1] + contact[i]) + external;
      const double held = reference.held[i] >= 0 ? b.prescribed[c] : 0.0;
      const double vn =
          reference.free_mask[i] ? v0[i] + b.dt * (total * reference.inv_mass[n] + b.gravity[c]) : held;
      EXPECT_EQ(with_rows.f[i], total) << n << " " << c;
      EXPECT_EQ(with_rows.v[i], vn) << n << " " << c;
      work3 += contact[i] * 0.5 * b.dt * (v0[i] + vn);
    }
  EXPECT_NEAR(r.work[3], work3, 1e-12 * std::abs(work3));
  EXPECT_NE(r.work[3], 0.0);
}

TEST(NodeIntegration, CountsNonFiniteNodes) {
  Problem p(100);
  p.joint_force[3 * 5 + 1] = std::nan("");
  size_t hit = 0;  // nodes that gather joint row 5 (slot 10 or 11) and integrate its y component
  for (size_t n = 0; n < p.nodes; ++n)
    for (int32_t k = p.node_range[2 * n]; k < p.node_range[2 * n + 1]; ++k)
      if ((p.slots[k] - p.first_slot[1]) / 2 == 5 && p.slots[k] >= p.first_slot[1] &&
          p.slots[k] < p.first_slot[2] && p.free_mask[3 * n + 1]) {
        ++hit;
        break;
      }
  const NodeStepResult r = integrate_nodes(p.args(), p.force_slots(), 0, p.nodes);
  EXPECT_EQ(r.non_finite, hit);
}

}  // namespace
}  // namespace rift::kernels

namespace rift::kernels {
namespace {

// Tets with 4 private nodes each (node 4 e + k is corner k of tet e), a joint on random pairs of their
// faces (side A's corners i facing side B's, as set-up pairs them), loaded-face slots on a few nodes: the
// slot lists the per-node pass reads and the face table the per-tet pass reads, of the same forces.
struct PrivateTets {
  Problem p;
  size_t tets;
  std::vector<int32_t> face_joint;
  std::vector<uint8_t> face_corners, loaded;

  explicit PrivateTets(size_t t) : tets(t) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const size_t nodes = 4 * t;
    face_joint.assign(4 * t, -1);
    face_corners.assign(4 * t, 0);
    loaded.assign(t, 0);
    // Joints between random free faces; each node's joint slots, in the order the joints are made.
    std::vector<std::vector<int32_t>> joint_slots(nodes);
    std::uniform_int_distribution<size_t> tet(0, t - 1);
    std::uniform_int_distribution<int> face(0, 3);
    size_t joints = 0;
    for (size_t attempt = 0; attempt < 3 * t; ++attempt) {
      const size_t ea = tet(rng), eb = tet(rng);
      const int fa = face(rng), fb = face(rng);
      if (ea == eb || face_joint[4 * ea + fa] >= 0 || face_joint[4 * eb + fb] >= 0) continue;
      const size_t j = joints++;
      unsigned ca = 0, cb = 0;
      for (int i = 0, ka = 0, kb = 0; i < 3; ++i, ++ka, ++kb) {
        if (ka == fa) ++ka;  // the face's corners: all but the opposite one
        if (kb == fb) ++kb;
        ca |= static_cast<unsigned>(ka) << (2 * i);
        cb |= static_cast<unsigned>(kb) << (2 * i);
        joint_slots[4 * ea + static_cast<size_t>(ka)].push_back(static_cast<int32_t>(2 * (3 * j + i) + 1));
        joint_slots[4 * eb + static_cast<size_t>(kb)].push_back(static_cast<int32_t>(2 * (3 * j + i)));
      }
      face_joint[4 * ea + fa] = static_cast<int32_t>(2 * j + 1);
      face_joint[4 * eb + fb] = static_cast<int32_t>(2 * j);
      face_corners[4 * ea + fa] = static_cast<uint8_t>(ca);
      face_corners[4 * eb + fb] = static_cast<uint8_t>(cb);
    }
    const size_t face_rows = t / 3 + 1;
    p.nodes = nodes;
    for (size_t k = 0; k < 12 * t; ++k) p.tet_force.push_back(1e3 * unit(rng));
    for (size_t k = 0; k < 9 * joints; ++k) p.joint_force.push_back(1e3 * unit(rng));
    for (size_t k = 0; k < 3 * face_rows; ++k) p.face_force.push_back(1e2 * unit(rng));
    p.first_slot[1] = static_cast<int64_t>(4 * t);
    p.first_slot[2] = p.first_slot[1] + static_cast<int64_t>(6 * joints);
    p.first_slot[3] = p.first_slot[2] + static_cast<int64_t>(face_rows);
    std::uniform_int_distribution<size_t> row(0, face_rows - 1);
    for (size_t n = 0; n < nodes; ++n) {
      p.node_range.push_back(static_cast<int32_t>(p.slots.size()));
      p.slots.push_back(static_cast<int32_t>(n));
      for (int32_t s : joint_slots[n]) p.slots.push_back(static_cast<int32_t>(p.first_slot[1]) + s);
      if (n % 7 == 0) {  // a loaded face or two
        for (size_t k = 0; k < 1 + n % 2; ++k)
          p.slots.push_back(static_cast<int32_t>(p.first_slot[2] + static_cast<int64_t>(row(rng))));
        loaded[n / 4] = 1;
      }
      p.node_range.push_back(static_cast<int32_t>(p.slots.size()));
    }
    for (size_t k = 0; k < 3 * nodes; ++k) {
      p.x.push_back(unit(rng));
      p.v.push_back(0.1 * unit(rng));
      p.free_mask.push_back(k % 17 == 0 ? 0 : 1);
      p.held.push_back(k % 34 == 0 ? 0 : -1);
    }
    p.f.assign(3 * nodes, 0.0);
    for (size_t n = 0; n < nodes; ++n) {
      p.mass.push_back(1e-3 * (1.5 + unit(rng)));
      p.inv_mass.push_back(n % 50 == 0 ? 0.0 : 1.0 / p.mass.back());
    }
    p.prescribed = {0.25, -0.5, 0.125};
  }
  PrivateTetForces tet_forces() const {
    return {p.tet_force, 0, 0, p.joint_force, face_joint, face_corners, loaded};
  }
};

// The per-tet gather adds a node's joint forces in face order instead of slot order: the same terms, so
// the results agree to rounding (1e-12 relative: a sum of up to 5 terms of 1e3 reordered differs by a
// few ulps of 1e3, far below 1e-12 of the velocity and force scales here).
TEST(NodeIntegration, PerTetGatherAgreesWithThePerNodeOne) {
  PrivateTets per_node(700), per_tet(700);
  const NodeStepResult a = integrate_nodes(per_node.p.args(), per_node.p.force_slots(), 0, per_node.p.nodes);
  const NodeStepResult b = integrate_private_tets(per_tet.p.args(), per_tet.tet_forces(),
                                                  per_tet.p.force_slots(), 0, per_tet.tets);
  for (size_t i = 0; i < per_node.p.x.size(); ++i) {
    ASSERT_NEAR(per_tet.p.f[i], per_node.p.f[i], 1e-12 * (1.0 + std::abs(per_node.p.f[i]))) << i;
    ASSERT_NEAR(per_tet.p.v[i], per_node.p.v[i], 1e-12 * (1.0 + std::abs(per_node.p.v[i]))) << i;
    ASSERT_NEAR(per_tet.p.x[i], per_node.p.x[i], 1e-15) << i;
  }
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(b.work[k], a.work[k], 1e-12 * (1e-9 + std::abs(a.work[k]))) << k;
  EXPECT_EQ(b.non_finite, a.non_finite);
  size_t with_joints = 0;
  for (int32_t r : per_tet.face_joint) with_joints += r >= 0;
  EXPECT_GT(with_joints, 1000u);  // most faces carry a joint
}

// Consecutive calls that pass the result on give the same bits as one call (the fused pass's runs).
TEST(NodeIntegration, PerTetGatherSameBitsForAnySplit) {
  PrivateTets whole(501), split(501);
  const NodeStepResult r =
      integrate_private_tets(whole.p.args(), whole.tet_forces(), whole.p.force_slots(), 0, whole.tets);
  NodeStepResult sum;
  for (size_t begin = 0, size = 1; begin < split.tets; begin += size, size = size * 2 + 1) {
    const size_t end = std::min(split.tets, begin + size);
    sum = integrate_private_tets(split.p.args(), split.tet_forces(), split.p.force_slots(), begin, end, sum);
  }
  EXPECT_EQ(whole.p.x, split.p.x);
  EXPECT_EQ(whole.p.v, split.p.v);
  EXPECT_EQ(whole.p.f, split.p.f);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(r.work[k], sum.work[k]) << k;
}

}  // namespace
}  // namespace rift::kernels
