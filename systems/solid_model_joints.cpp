// SolidModel set-up of the fracture zone: the joint table, joint materials per pair of tet materials,
// the in-situ state of every joint, and the bookkeeping tables (fracture events, energy integrals).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "engine/core/error.hpp"
#include "kernels/joint_initial_state.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {

kernels::JointMaterial joint_material(const FractureMaterialSpec& f) {
  return {f.penalty, f.tensile_strength, f.cohesion, std::tan(f.friction_angle * M_PI / 180.0), f.G_I,
          f.G_II,    f.residual_friction};
}

// An interface between two materials is as weak as the weaker of them in every property.
kernels::JointMaterial weaker(const kernels::JointMaterial& a, const kernels::JointMaterial& b) {
  return {std::min(a.penalty, b.penalty),
          std::min(a.tensile_strength, b.tensile_strength),
          std::min(a.cohesion, b.cohesion),
          std::min(a.tan_friction, b.tan_friction),
          std::min(a.G_I, b.G_I),
          std::min(a.G_II, b.G_II),
          std::min(a.residual_friction, b.residual_friction)};
}

}  // namespace

void SolidModel::build_joints(const DiscontinuousMesh& dm) {
  const FractureSpec& f = *spec_.fracture;
  const int points = f.integration_points;
  Table& joints = store_.add_table(solid::joint_table);
  solid::joint::nodes.create(joints).indexes(IndexTarget::rows_of(solid::node_table));
  solid::joint::tets.create(joints).indexes(IndexTarget::rows_of(solid::tet_table));
  solid::joint::material.create(joints);
  solid::joint::d_max.create(joints, points);
  solid::joint::broken.create(joints);
  solid::joint::corner_force.create(joints);  // side B's corners; side A's are minus these
  solid::joint::opening.create(joints);
  solid::joint::slip.create(joints);
  solid::joint::damage.create(joints);
  solid::joint::stored_energy.create(joints);
  solid::joint::initial_offset.create(joints);
  joints.resize(dm.joints.size());
  auto nodes = solid::joint::nodes.in(joints);
  auto tets = solid::joint::tets.in(joints);
  auto material = solid::joint::material.in(joints);
  const auto tet_material = solid::tet::material.read(store_);

  // One joint material per distinct (material A, material B) pair, in order of first appearance.
  std::map<std::pair<int32_t, int32_t>, int32_t> pair_index;
  for (size_t j = 0; j < dm.joints.size(); ++j) {
    for (int k = 0; k < 6; ++k) nodes[6 * j + k] = dm.joints[j][k];
    const auto [a, b] = dm.joint_tets[j];
    tets[2 * j] = a;
    tets[2 * j + 1] = b;
    const int32_t ma = tet_material[a], mb = tet_material[b];
    const auto key = std::make_pair(std::min(ma, mb), std::max(ma, mb));
    auto it = pair_index.find(key);
    if (it == pair_index.end()) {
      const auto& A = spec_.materials[key.first].fracture;
      const auto& B = spec_.materials[key.second].fracture;
      for (const int32_t m : {key.first, key.second})
        if (!spec_.materials[m].fracture && dm.tet_in_zone[m == ma ? a : b])
          throw Error("solid.materials[" + std::to_string(m) + "] ('" + spec_.materials[m].name +
                      "') fills tets of the fracture zone (solid.fracture) but has no fracture properties; "
                      "add solid.materials[" +
                      std::to_string(m) +
                      "].fracture with tensile_strength, cohesion, friction_angle, G_I and G_II");
      const kernels::JointMaterial jm =
          A && B ? weaker(joint_material(*A), joint_material(*B)) : joint_material(A ? *A : *B);
      it = pair_index.emplace(key, static_cast<int32_t>(joint_materials_.size())).first;
      joint_materials_.push_back(jm);
    }
    material[j] = it->second;
  }
  solid::joint::material.column(store_).indexes(IndexTarget::list_of(joint_materials_.size()));
  // The residual-friction slider's anchors (kernels/joint_law.hpp), only where some material has one.
  if (std::any_of(joint_materials_.begin(), joint_materials_.end(),
                  [](const kernels::JointMaterial& m) { return m.residual_friction > 0.0; })) {
    solid::joint::residual_anchor.create(joints, 3 * points);
  }
  if (spec_.initial_stress) set_joint_initial_state();
}

// Every joint starts carrying the in-situ traction sigma0 . n: its two sides are offset so that the law
// gives exactly that traction (kernels/joint_initial_state.hpp). Without this the joints would start
// unloaded while the tets are stressed, and the mismatch would launch a wave at t = 0.
void SolidModel::set_joint_initial_state() {
  Table& joints = store_.table(solid::joint_table);
  const auto x = solid::node::x0.read(store_);
  const auto nodes = solid::joint::nodes.read(joints);
  const auto material = solid::joint::material.read(joints);
  auto offset = solid::joint::initial_offset.in(joints);
  const auto& S = initial_stress_;
  const kernels::Softening rule =
      spec_.fracture->y_compatible ? kernels::Softening::y_compatible : kernels::Softening::energy_exact;
  const double Z = kernels::softening_integral();
  for (size_t j = 0; j < joints.size(); ++j) {
    const double* p[3] = {&x[3 * nodes[6 * j]], &x[3 * nodes[6 * j + 1]], &x[3 * nodes[6 * j + 2]]};
    double e[3][3], h = INFINITY;
    for (int i = 0; i < 3; ++i) {
      for (int c = 0; c < 3; ++c) e[i][c] = p[(i + 1) % 3][c] - p[i][c];
      h = std::min(h, std::sqrt(e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2]));
    }
    double n[3] = {e[0][1] * (-e[2][2]) - e[0][2] * (-e[2][1]), e[0][2] * (-e[2][0]) - e[0][0] * (-e[2][2]),
                   e[0][0] * (-e[2][1]) - e[0][1] * (-e[2][0])};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n) c /= len;
    const double t[3] = {S[0] * n[0] + S[3] * n[1] + S[5] * n[2], S[3] * n[0] + S[1] * n[1] + S[4] * n[2],
                         S[5] * n[0] + S[4] * n[1] + S[2] * n[2]};
    if (!kernels::joint_initial_offset(joint_materials_[material[j]], h, n, t, rule, Z, &offset[3 * j]))
      throw Error("solid.initial_stress: the in-situ traction on joint " + std::to_string(j) + " at (" +
                  std::to_string(p[0][0]) + ", " + std::to_string(p[0][1]) + ", " + std::to_string(p[0][2]) +
                  ") m reaches its strength (tension above tensile_strength or shear above the Mohr-Coulomb "
                  "envelope), so the rock would be broken before the run starts. Lower the in-situ "
                  "deviatoric stress or raise the strengths of the zone's materials.");
  }
}

void SolidModel::create_bookkeeping_tables() {
  Table& events = store_.add_table(solid::event_table);
  solid::event::step.create(events);
  solid::event::time.create(events);
  // Without joints nothing breaks: the log stays empty, and any index in it is wrong.
  solid::event::joint.create(events).indexes(
      store_.has(solid::joint_table) ? IndexTarget::rows_of(solid::joint_table) : IndexTarget::list_of(0));
  solid::event::mode.create(events);
  solid::event::centroid.create(events);
  solid::event::normal.create(events);
  solid::event::area.create(events);
  solid::event::released_energy.create(events);
  Table& energy = store_.add_table(solid::energy_table);
  for (const auto& c : {solid::energy::external_work, solid::energy::tet_work, solid::energy::joint_work,
                        solid::energy::damping, solid::energy::joint_energy0, solid::energy::kinetic0})
    c.create(energy);
  energy.resize(1);
}

}  // namespace rift

namespace rift {

// Joints on the planes of solid.fracture.initial_cracks start broken: mode 3 in the joint table and one
// row each at the head of the fracture log (step -1, time 0), so the mesh conversion and the contact
// see them like any break, while the fracture energy (joint work) stays zero.
void SolidModel::apply_initial_cracks(const std::vector<uint8_t>& zone) {
  if (spec_.fracture->initial_cracks.empty()) return;
  Table& joints = store_.table(solid::joint_table);
  const auto x0 = solid::node::x0.read(store_);
  // A vertex that a tet outside the zone uses has one shared node for all such tets: where they touch
  // the crack from both sides (by an edge or a vertex), that node holds the crack shut.
  const auto node_vertex = solid::node::vertex.read(store_);
  const auto tet_nodes = solid::tet::nodes.read(store_);
  std::vector<uint8_t> outside_vertex;
  for (size_t e = 0; e < zone.size(); ++e)
    if (!zone[e])
      for (int k = 0; k < 4; ++k) {
        const auto v = static_cast<size_t>(node_vertex[tet_nodes[4 * e + k]]);
        if (v >= outside_vertex.size()) outside_vertex.resize(v + 1, 0);
        outside_vertex[v] = 1;
      }
  size_t tied = 0;
  const double* first_tied = nullptr;
  const auto conn = solid::joint::nodes.read(joints);
  auto broken = solid::joint::broken.in(joints);
  Table& events = store_.table(solid::event_table);
  size_t cracked = 0;
  for (size_t j = 0; j < joints.size(); ++j) {
    const double* p[3] = {&x0[3 * conn[6 * j]], &x0[3 * conn[6 * j + 1]], &x0[3 * conn[6 * j + 2]]};
    double edge = 0.0, centroid[3], n[3];
    for (int i = 0; i < 3; ++i) centroid[i] = (p[0][i] + p[1][i] + p[2][i]) / 3.0;
    for (int a = 0; a < 3; ++a) {
      const double* q = p[(a + 1) % 3];
      edge = std::max(edge, std::hypot(q[0] - p[a][0], q[1] - p[a][1], q[2] - p[a][2]));
    }
    bool on_crack = false;
    for (const CrackPlaneSpec& c : spec_.fracture->initial_cracks) {
      const double len = std::hypot(c.normal[0], c.normal[1], c.normal[2]);
      bool on = true;
      for (int a = 0; a < 3 && on; ++a) {
        const double d = ((p[a][0] - c.point[0]) * c.normal[0] + (p[a][1] - c.point[1]) * c.normal[1] +
                          (p[a][2] - c.point[2]) * c.normal[2]) /
                         len;
        on = std::abs(d) <= 1e-6 * edge;
      }
      if (on && c.radius)
        on = std::hypot(centroid[0] - c.point[0], centroid[1] - c.point[1], centroid[2] - c.point[2]) <=
             *c.radius;
      on_crack = on_crack || on;
    }
    if (!on_crack) continue;
    for (int a = 0; a < 3; ++a) {
      const auto v = static_cast<size_t>(node_vertex[conn[6 * j + a]]);
      if (v < outside_vertex.size() && outside_vertex[v]) {
        if (!first_tied) first_tied = p[a];
        ++tied;
      }
    }
    broken[j] = 3;
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
    const double area2 = std::hypot(n[0], n[1], n[2]);
    const size_t row = events.size();
    events.resize(row + 1);
    solid::event::step.in(events)[row] = -1;
    solid::event::time.in(events)[row] = 0.0;
    solid::event::joint.in(events)[row] = static_cast<int32_t>(j);
    solid::event::mode.in(events)[row] = 3;
    for (int i = 0; i < 3; ++i) {
      solid::event::centroid.in(events)[3 * row + i] = centroid[i];
      solid::event::normal.in(events)[3 * row + i] = area2 > 0 ? n[i] / area2 : 0.0;
    }
    solid::event::area.in(events)[row] = 0.5 * area2;
    ++cracked;
  }
  if (cracked == 0)
    throw Error(
        "solid.fracture.initial_cracks: no joint lies on any of the planes; the mesh needs faces on "
        "the crack plane (a lattice mesh, or a mesh file with the crack as an internal surface), and "
        "the plane must cross the fracture zone");
  if (tied > 0)
    throw Error(fmt::format(
        "solid.fracture.initial_cracks: {} corners of crack joints are vertices that tets outside the "
        "fracture zone share (first at ({:.6g}, {:.6g}, {:.6g}) m), so the crack is held shut there. Make "
        "solid.fracture.box_min / box_max (or regions) take in every tet that touches the crack, e.g. one "
        "whole layer of elements on each side of it",
        tied, first_tied[0], first_tied[1], first_tied[2]));
  spdlog::info("solid: {} joints start broken on {} initial crack plane(s)", cracked,
               spec_.fracture->initial_cracks.size());
}

// The contact penalty defaults, with joints, to one per tet matched to them (contact_system.hpp): a joint
// broken under compression hands its load to a contact spring no stiffer than itself, and the contact does
// not shorten the step. Without joints (separate bodies) it is 10 x the stiffest material (femdem.md 1d:
// 10-100 E). A chosen penalty far stiffer than the matched ones gets a warning.
void SolidModel::build_contact(const TetMesh& mesh) {
  ContactSpec contact = *spec_.contact;
  std::vector<double> matched;
  if (joint_count() > 0) {
    std::vector<double> joint_penalty;
    for (const auto& m : joint_materials_) joint_penalty.push_back(m.penalty);
    matched = matched_contact_penalties(store_, joint_penalty);
  }
  if (!contact.penalty && matched.empty()) {
    double young = 0.0;
    for (const auto& m : spec_.materials) young = std::max(young, m.young);
    contact.penalty = 10.0 * young;
  }
  const double mean = matched.empty() ? 0.0
                                      : std::accumulate(matched.begin(), matched.end(), 0.0) /
                                            static_cast<double>(matched.size());
  if (contact.penalty && !matched.empty() && *contact.penalty > 2.0 * mean) {
    spdlog::warn(
        "solid.contact.penalty {:.4g} Pa is {:.1f} x the mean penalty matched to the joints ({:.4g} Pa): a "
        "joint broken under compression hands its load to a much stiffer spring, which throws the faces "
        "apart (the contact guard may stop the run) and shortens the step; leave the key out to use the "
        "matched ones",
        *contact.penalty, *contact.penalty / mean, mean);
  }
  const Table& tets = store_.table(solid::tet_table);
  const auto material = solid::tet::material.read(tets);
  std::vector<double> density(tets.size());
  for (size_t e = 0; e < tets.size(); ++e) density[e] = spec_.materials[material[e]].density;
  contact_ = std::make_unique<ContactSystem>(store_, contact, mesh.nodes.size(), density, std::move(matched));
}

}  // namespace rift

namespace rift {

// With solid.fracture.crack_pressure, every joint gets its two faces as loaded faces (face 2j + s is the
// face of joint j on tets[s], oriented out of that tet), all tied to one pressure condition. The surface
// load system presses only the faces of broken joints, so an intact joint's rows stay zero. They have no
// force slots: the surface loads gather the pressed faces' corner forces into solid_node.crack_force,
// which the node pass reads as an external force.
void SolidModel::add_crack_faces() {
  store_.table(solid::node_table).add<double>(node_force_column(NodeForceSource::crack), 3);
  const Table& joints = store_.table(solid::joint_table);
  const auto jn = solid::joint::nodes.read(joints);
  const auto jt = solid::joint::tets.read(joints);
  const auto tet_nodes = solid::tet::nodes.read(store_);
  const auto x0 = solid::node::x0.read(store_);
  Table& faces = store_.table(solid::face_table);
  const size_t first = faces.size();
  faces.resize(first + 2 * joints.size());
  auto face_nodes = solid::face::nodes.in(faces);
  auto face_load = solid::face::load.in(faces);
  const int32_t load = static_cast<int32_t>(load_conditions_.size());
  for (size_t j = 0; j < joints.size(); ++j)
    for (int s = 0; s < 2; ++s) {
      const int32_t* tri = &jn[6 * j + 3 * s];
      const int32_t* tet = &tet_nodes[4 * static_cast<size_t>(jt[2 * j + s])];
      int32_t apex = -1;
      for (int k = 0; k < 4; ++k)
        if (tet[k] != tri[0] && tet[k] != tri[1] && tet[k] != tri[2]) apex = tet[k];
      if (apex < 0) throw Error("internal: joint " + std::to_string(j) + " face is not a face of its tet");
      const double* p0 = &x0[3 * tri[0]];
      const double* p1 = &x0[3 * tri[1]];
      const double* p2 = &x0[3 * tri[2]];
      const double* pa = &x0[3 * apex];
      double a[3], c[3], d[3];
      for (int i = 0; i < 3; ++i) a[i] = p1[i] - p0[i], c[i] = p2[i] - p0[i], d[i] = pa[i] - p0[i];
      const double n[3] = {a[1] * c[2] - a[2] * c[1], a[2] * c[0] - a[0] * c[2], a[0] * c[1] - a[1] * c[0]};
      const bool outward = n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0;
      const size_t f = first + 2 * j + static_cast<size_t>(s);
      face_nodes[3 * f] = tri[0];
      face_nodes[3 * f + 1] = outward ? tri[1] : tri[2];
      face_nodes[3 * f + 2] = outward ? tri[2] : tri[1];
      face_load[f] = load;
    }
  SolidBoundarySpec crack;
  crack.kind = SolidBoundarySpec::Kind::pressure;
  crack.surface = "solid.fracture.crack_pressure";
  crack.function = *spec_.fracture->crack_pressure;
  load_conditions_.push_back(crack);
  solid::face::load.column(store_).indexes(IndexTarget::list_of(load_conditions_.size()));
}

}  // namespace rift
