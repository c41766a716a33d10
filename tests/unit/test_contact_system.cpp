// The contact system's set-up and its sleep: block meshes, initial cracks, the scene keys, and no work in a
// scene of one intact body (the physics is in tests/validation/test_contact.cpp).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "engine/mesh/block_assembly.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

using namespace rift;

namespace {

Scene validation(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/" + name, overrides);
}

std::unique_ptr<Simulation> start(const Scene& scene) {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  return std::make_unique<Simulation>(scene, o);
}

const Table& table(Simulation& sim, const char* name) {
  return sim.world().store.table(name);
}

}  // namespace

TEST(BlockAssembly, BlocksAreSeparateBodiesWithPrefixedSurfaces) {
  std::vector<BlockSpec> blocks(2);
  blocks[0] = {"a", {0, 0, 0}, {1, 1, 1}, {2, 1, 1}, std::nullopt};
  blocks[1] = {"b", {0, 0, 2}, {1, 2, 1}, {1, 2, 1}, std::nullopt};
  const TetMesh m = generate_block_assembly(blocks);
  EXPECT_EQ(m.tets.size(), 6u * 2 + 6u * 2);
  EXPECT_EQ(m.nodes.size(), 12u + 12u);
  ASSERT_EQ(m.region_names, (std::vector<std::string>{"a", "b"}));
  EXPECT_GE(m.surface_index("a_xmin"), 0);
  EXPECT_GE(m.surface_index("b_zmax"), 0);
  for (size_t e = 0; e < m.tets.size(); ++e)  // no node is shared between the blocks
    for (int32_t n : m.tets[e]) EXPECT_EQ(n < 12, m.tet_region[e] == 0);
  EXPECT_DOUBLE_EQ(m.nodes.back()[2], 3.0);  // origin applied
  blocks[1].name = "a";
  EXPECT_THROW(generate_block_assembly(blocks), Error);
}

TEST(ContactScene, KeysAreReadWithDefaults) {
  const Scene s = validation("contact_incline.yaml");
  ASSERT_TRUE(s.solid->contact);
  EXPECT_FALSE(s.solid->contact->penalty);  // resolved by the solid: 10 x young
  EXPECT_DOUBLE_EQ(s.solid->contact->friction, 0.3);
  EXPECT_DOUBLE_EQ(s.solid->contact->tangential_penalty, 0.1);
  EXPECT_DOUBLE_EQ(s.solid->contact->damping, 0.2);
  EXPECT_EQ(s.mesh.generate->shape, MeshGenerateSpec::Shape::blocks);
  EXPECT_EQ(s.mesh.generate->blocks[1].cells, (std::array<int, 3>{2, 2, 2}));
}

TEST(ContactScene, BadValuesAreErrorsAtTheirKey) {
  auto error_of = [](const std::vector<std::string>& overrides) {
    try {
      validation("contact_incline.yaml", overrides);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of({"solid.contact.friction=-1"}).find("solid.contact.friction"), std::string::npos);
  EXPECT_NE(error_of({"solid.contact.damping=2"}).find("solid.contact.damping"), std::string::npos);
  EXPECT_NE(error_of({"solid.contact.penalty=0"}).find("solid.contact.penalty"), std::string::npos);
  EXPECT_NE(error_of({"solid.contact.frction=0.2"}).find("friction"), std::string::npos);  // did you mean
  EXPECT_NE(error_of({"mesh.generate.blocks[0].cells=[1.5, 1, 1]"}).find("whole numbers"), std::string::npos);
  EXPECT_NE(error_of({"mesh.generate.size_min=0.01"}).find("for blocks"), std::string::npos);
}

TEST(InitialCracks, JointsOnThePlaneStartBrokenWithoutFractureEnergy) {
  auto sim = start(validation("contact_cut_column.yaml"));
  const Table& events = table(*sim, solid::event_table);
  ASSERT_EQ(events.size(), 8u);  // 2 x 2 cubes, 2 triangles each, on z = 0.02
  for (size_t r = 0; r < events.size(); ++r) {
    EXPECT_EQ(events.span<const uint8_t>("mode")[r], 3);
    EXPECT_EQ(events.span<const int64_t>("step")[r], -1);
    EXPECT_NEAR(events.span<const double>("centroid")[3 * r + 2], 0.02, 1e-12);
    EXPECT_NEAR(std::abs(events.span<const double>("normal")[3 * r + 2]), 1.0, 1e-12);
  }
  size_t broken = 0;
  for (uint8_t b : table(*sim, solid::joint_table).span<const uint8_t>("broken")) broken += b == 3;
  EXPECT_EQ(broken, 8u);
  for (int i = 0; i < 5; ++i) sim->step_once();
  SolidModel* solid = nullptr;
  for (auto& m : sim->world().models)
    if (auto* s = dynamic_cast<SolidModel*>(m.get())) solid = s;
  ASSERT_NE(solid, nullptr);
  // Nothing dissipated. Breaking the plane would cost G_I x 0.02 x 0.02 m^2 = 4 J; what is booked is only
  // the gap between the intact joints' work (trapezoidal in time) and their stored energy (exact), which
  // five steps after the start of the motion is of the order of that stored energy (1e-11 J).
  const SolidEnergies e = solid->energies();
  EXPECT_LT(std::abs(e.fracture), 1e-9 * 1.0e4 * 0.02 * 0.02);
  EXPECT_LT(std::abs(e.fracture), std::abs(e.joint_stored));
}

TEST(InitialCracks, APlaneThatMeetsNoJointIsAnError) {
  const Scene scene =
      validation("contact_cut_column.yaml", {"solid.fracture.initial_cracks[0].point=[0, 0, 0.015]"});
  try {
    start(scene);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("initial_cracks"), std::string::npos) << e.what();
  }
}

// Model only what a scene requires: one intact body with a fracture zone and contact on has no candidates,
// detects nothing and allocates no pairs until a joint breaks.
TEST(ContactSystem, SleepsInOneIntactBody) {
  auto sim = start(validation("contact_cut_column.yaml", {"solid.fracture.initial_cracks=[]"}));
  for (int i = 0; i < 50; ++i) sim->step_once();
  EXPECT_EQ(table(*sim, solid::contact_pair_table).size(), 0u);
  EXPECT_EQ(table(*sim, solid::contact_state_table).span<const int64_t>("detections")[0], 0);
  // With the crack, the same scene wakes at once: the crack's tets pair up across it.
  auto cracked = start(validation("contact_cut_column.yaml"));
  cracked->step_once();
  EXPECT_GT(table(*cracked, solid::contact_pair_table).size(), 0u);
  EXPECT_EQ(table(*cracked, solid::contact_state_table).span<const int64_t>("detections")[0], 1);
}

TEST(ContactSystem, MatchedPenaltiesAreNeverStifferThanTheJointsAndLeaveTheStepToThem) {
  // Without solid.contact.penalty, a jointed scene gets one penalty per tet: on each joint face, each side's
  // 4 p_t / H is at most half the joint's p_j / h, so the contact never sets the stable step.
  const Scene scene = validation("contact_cut_column.yaml");
  ASSERT_TRUE(scene.solid->contact.has_value());
  ASSERT_FALSE(scene.solid->contact->penalty.has_value());
  auto sim = start(scene);
  const Store& store = sim->world().store;
  const double p_j = scene.solid->materials[0].fracture->penalty;
  const std::vector<double> p = matched_contact_penalties(store, std::vector<double>{p_j});
  const auto x0 = store.table(solid::node_table).span<const double>("x0");
  const auto conn = store.table(solid::tet_table).span<const int32_t>("nodes");
  const Table& joints = store.table(solid::joint_table);
  const auto jn = joints.span<const int32_t>("nodes");
  const auto jt = joints.span<const int32_t>("tets");
  auto point = [&](int32_t n) { return Eigen::Vector3d(x0[3 * n], x0[3 * n + 1], x0[3 * n + 2]); };
  size_t tight = 0;
  for (size_t j = 0; j < joints.size(); ++j) {
    const Eigen::Vector3d a = point(jn[6 * j]), b = point(jn[6 * j + 1]), c = point(jn[6 * j + 2]);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double h = std::min({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    for (int s = 0; s < 2; ++s) {
      const int32_t t = jt[2 * j + s];
      const Eigen::Vector3d q0 = point(conn[4 * t]), q1 = point(conn[4 * t + 1]), q2 = point(conn[4 * t + 2]),
                            q3 = point(conn[4 * t + 3]);
      const double volume = std::abs((q1 - q0).dot((q2 - q0).cross(q3 - q0))) / 6.0;
      const double side = 4.0 * p[t] / (3.0 * volume / area);
      EXPECT_LE(side, 0.5 * p_j / h * (1 + 1e-12)) << "joint " << j << " side " << s;
      tight += side > 0.5 * p_j / h * (1 - 1e-12);
    }
  }
  EXPECT_GT(tight, 0u);  // the minimum is attained on some face of every tet
  nlohmann::json summary;
  sim->world().models[0]->summarize(summary);
  const double dt_t = summary["solid"]["tet_stable_dt"], dt_j = summary["solid"]["joint_stable_dt"];
  // The contact's stiffness leaves the step to the tets and joints; its explicit damping (eta_n / k_n per
  // unit stiffness) shortens it by sqrt(1 + xi^2) - xi (ContactSystem::damped_step).
  const double undamped = 1.0 / std::sqrt(1.0 / (dt_t * dt_t) + 3.0 / (dt_j * dt_j));
  const double dt_c = summary["solid"]["contact"]["stable_dt"],
               c = summary["solid"]["contact"]["damping_time"];
  ASSERT_GT(c, 0.0);
  const double xi = c * undamped / (dt_c * dt_c);
  EXPECT_DOUBLE_EQ(summary["solid"]["stable_dt"].get<double>(), undamped * (std::sqrt(1.0 + xi * xi) - xi));
}

// A softening joint can hinge about the line through its compressed integration points, which do not see
// its corners overlap the neighbour; tied by the joint, the pair was excluded from contact until the joint
// broke, and the contact then met the whole overlap at once (docs/contact.md, "Who takes part"). From its
// first damage a joint's two tets take part, tied or not, and a restart keeps them (the joint's in_contact).
TEST(ContactSystem, ADamagedJointsTetsTakePartWhileTheJointStillHolds) {
  auto sim = start(validation("contact_cut_column.yaml"));
  sim->step_once();  // the initial crack wakes the system
  Table& joints = sim->world().store.table(solid::joint_table);
  const auto broken = joints.span<const uint8_t>("broken");
  const auto tets = joints.span<const int32_t>("tets");
  auto in_contact = joints.span<uint8_t>("in_contact");
  auto pair_listed = [&](size_t j) {
    const Table& pairs = table(*sim, solid::contact_pair_table);
    const auto listed = pairs.span<const int32_t>("tets");
    const int32_t a = std::min(tets[2 * j], tets[2 * j + 1]), b = std::max(tets[2 * j], tets[2 * j + 1]);
    for (size_t p = 0; p < pairs.size(); ++p)
      if (listed[2 * p] == a && listed[2 * p + 1] == b) return true;
    return false;
  };
  size_t intact = joints.size();
  for (size_t j = 0; j < joints.size() && intact == joints.size(); ++j)
    if (broken[j] == 0 && !pair_listed(j)) intact = j;
  ASSERT_LT(intact, joints.size()) << "every intact joint's pair is already in contact";
  EXPECT_EQ(in_contact[intact], 0);

  const size_t points = joints.span<const double>("d_max").size() / joints.size();
  // One integration point half way to failure, booked as the joint kernel books an onset.
  joints.span<double>("d_max")[points * intact] = 0.5;
  sim->world().store.table(solid::joint_state_table).span<int64_t>("damage_onsets")[0] += 1;
  sim->step_once();
  EXPECT_EQ(in_contact[intact], 1);
  EXPECT_TRUE(pair_listed(intact)) << "joint " << intact << " is damaged but its tets are still excluded";
  EXPECT_EQ(broken[intact], 0);
}
