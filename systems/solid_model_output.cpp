// SolidModel outputs: field grids (tets, and joints as wedge cells), time-series metrics with the energy
// balance, and the fracture log.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/io/atomic_file.hpp"
#include "engine/scene/output_fields.hpp"
#include "engine/scene/suggest.hpp"
#include "kernels/reproducible_sum.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {

// Symmetric 3x3 eigenvalues (descending) by the trigonometric formula: exact for a symmetric matrix,
// adequate at output time. s = xx yy zz xy yz zx.
void principal_values(const double* s, double* out) {
  const double p1 = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  const double q = (s[0] + s[1] + s[2]) / 3.0;
  if (p1 <= 1e-30 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) + 1e-300) {
    double d[3] = {s[0], s[1], s[2]};
    std::sort(d, d + 3, std::greater<>());
    std::copy(d, d + 3, out);
    return;
  }
  const double p2 = (s[0] - q) * (s[0] - q) + (s[1] - q) * (s[1] - q) + (s[2] - q) * (s[2] - q) + 2 * p1;
  const double p = std::sqrt(p2 / 6.0);
  const double b[6] = {(s[0] - q) / p, (s[1] - q) / p, (s[2] - q) / p, s[3] / p, s[4] / p, s[5] / p};
  const double det = b[0] * (b[1] * b[2] - b[4] * b[4]) - b[3] * (b[3] * b[2] - b[4] * b[5]) +
                     b[5] * (b[3] * b[4] - b[1] * b[5]);
  const double r = std::clamp(det / 2.0, -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  out[0] = q + 2 * p * std::cos(phi);
  out[2] = q + 2 * p * std::cos(phi + 2.0 * M_PI / 3.0);
  out[1] = 3 * q - out[0] - out[2];
}

}  // namespace

void SolidModel::output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {
  const Table& nodes = store_.table(solid::node_table);
  const Table& tets = store_.table(solid::tet_table);
  const auto x = solid::node::x.in(nodes);
  const auto x0 = solid::node::x0.in(nodes);
  displacement_.resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) displacement_[i] = x[i] - x0[i];
  const auto stress = solid::tet::stress.in(tets);
  principal_.resize(3 * tets.size());
  for (size_t e = 0; e < tets.size(); ++e) principal_values(&stress[6 * e], &principal_[3 * e]);
  // The store keeps xx yy zz xy yz zx (Voigt); XDMF's Tensor6 is xx xy xz yy yz zz, and ParaView's XDMF
  // Reader expands it to the full tensor in that order: written as stored, its YY would hold sigma_xy.
  stress_tensor6_.resize(6 * tets.size());
  for (size_t e = 0; e < tets.size(); ++e) {
    const double* s = &stress[6 * e];
    double* o = &stress_tensor6_[6 * e];
    o[0] = s[0];
    o[1] = s[3];
    o[2] = s[5];
    o[3] = s[1];
    o[4] = s[4];
    o[5] = s[2];
  }

  XdmfGrid g{"solid",
             Topology::tetrahedron,
             x.data(),
             nodes.size(),
             solid::tet::nodes.in(tets).data(),
             tets.size(),
             0,
             true,
             {}};
  auto node_field = [&](const char* name, const double* data) {
    if (wants_field(fields, name))
      g.fields.push_back({name, Center::node, 3, ElementType::f64, data, nodes.size()});
  };
  auto cell_field = [&](XdmfGrid& grid, const char* name, int components, ElementType type,
                        const void* data) {
    if (wants_field(fields, name))
      grid.fields.push_back({name, Center::cell, components, type, data, grid.cell_count});
  };
  node_field("displacement", displacement_.data());
  node_field("velocity", solid::node::v.in(nodes).data());
  node_field("force", solid::node::f.in(nodes).data());
  if (contact_)
    node_field("contact_force", nodes.span<double>(node_force_column(NodeForceSource::contact)).data());
  cell_field(g, "stress", 6, ElementType::f64, stress_tensor6_.data());
  cell_field(g, "principal_stress", 3, ElementType::f64, principal_.data());
  cell_field(g, "energy", 1, ElementType::f64, solid::tet::energy.in(tets).data());
  cell_field(g, "region", 1, ElementType::i32, solid::tet::region.in(tets).data());
  cell_field(g, "material", 1, ElementType::i32, solid::tet::material.in(tets).data());
  grids.push_back(std::move(g));
  if (!store_.has(solid::joint_table)) return;

  // Joints as wedge cells on the same points: corners 0-2 (side A) and 3-5 (side B) are VTK_WEDGE's two
  // triangles, so a joint opens visibly in ParaView. Topology is fixed (broken joints stay, flagged).
  const Table& joints = store_.table(solid::joint_table);
  XdmfGrid j{"joints",
             Topology::wedge,
             x.data(),
             nodes.size(),
             solid::joint::nodes.in(joints).data(),
             joints.size(),
             0,
             true,
             {}};
  cell_field(j, "damage", 1, ElementType::f64, solid::joint::damage.in(joints).data());
  cell_field(j, "opening", 1, ElementType::f64, solid::joint::opening.in(joints).data());
  cell_field(j, "slip", 1, ElementType::f64, solid::joint::slip.in(joints).data());
  cell_field(j, "broken", 1, ElementType::u8, solid::joint::broken.in(joints).data());
  cell_field(j, "energy", 1, ElementType::f64, solid::joint::stored_energy.in(joints).data());
  grids.push_back(std::move(j));
}

SolidEnergies SolidModel::energies() const {
  const Table& nodes = store_.table(solid::node_table);
  const auto v = solid::node::v.read(nodes);
  const auto m = solid::node::mass.read(nodes);
  // The sums over rows are order-free (kernels/reproducible_sum.hpp), as the step's energy books are: the
  // same bits whichever process holds which rows.
  SolidEnergies e;
  e.kinetic = total_over(Rows::nodes, nodes.size(), [&](size_t n) {
    return 0.5 * m[n] * (v[3 * n] * v[3 * n] + v[3 * n + 1] * v[3 * n + 1] + v[3 * n + 2] * v[3 * n + 2]);
  });
  const auto tet_energy = solid::tet::energy.read(store_);
  e.elastic = total_over(Rows::tets, tet_energy.size(), [&](size_t t) { return tet_energy[t]; });
  const Table& book = store_.table(solid::energy_table);
  // Kinetic energy at t = 0 (an initial velocity) counts as work done before the run.
  e.external_work = solid::energy::external_work.read(book)[0] + solid::energy::kinetic0.read(book)[0];
  e.damping = solid::energy::damping.read(book)[0];
  if (store_.has(solid::joint_table)) {
    const auto stored = solid::joint::stored_energy.read(store_);
    e.joint_stored = total_over(Rows::joints, stored.size(), [&](size_t j) { return stored[j]; }) -
                     solid::energy::joint_energy0.read(book)[0];
    // Work done on the joints that they do not store is what fracture (and the law's hysteresis) took,
    // less what broken joints still held when they broke.
    const auto released = solid::event::released_energy.read(store_);
    e.break_release = total_over(Rows::events, released.size(), [&](size_t r) { return released[r]; });
    e.fracture = -solid::energy::joint_work.read(book)[0] - e.joint_stored - e.break_release;
  }
  if (contact_) {
    // Stored in the overlaps and the friction springs: what the contact forces took (minus their work)
    // less what friction and damping dissipated. The kernel's direct overlap energy is not used: its
    // boundary integral does not close where faces lie in each other's planes (lattice faces touching).
    e.friction = solid::energy::friction.read(book)[0];
    e.contact_stored = -solid::energy::contact_work.read(book)[0] - e.friction -
                       solid::energy::contact_damping.read(book)[0];
    e.contact_damping = solid::energy::contact_damping.read(book)[0];
  }
  return e;
}

void SolidModel::metrics(double time, std::vector<std::pair<std::string, double>>& row) {
  const SolidEnergies e = energies();
  row.emplace_back("solid_kinetic_energy", e.kinetic);
  row.emplace_back("solid_elastic_energy", e.elastic);
  row.emplace_back("solid_joint_energy", e.joint_stored);
  row.emplace_back("solid_damping_dissipation", e.damping);
  row.emplace_back("solid_fracture_dissipation", e.fracture);
  row.emplace_back("solid_break_release", e.break_release);
  row.emplace_back("solid_external_work", e.external_work);
  row.emplace_back("solid_energy_balance_error", e.balance_error());
  row.emplace_back("solid_broken_joints", static_cast<double>(broken_joint_count()));
  if (store_.has(solid::joint_table)) {
    // Volume between the faces of the broken joints: opening (normal, geometric) x area at the break.
    // What a pressurised crack's opening volume is checked against (Sneddon), and what a fluid fills.
    const Table& ev = store_.table(solid::event_table);
    const auto joint = solid::event::joint.read(ev);
    const auto area = solid::event::area.read(ev);
    const auto opening = solid::joint::opening.read(store_);
    double volume = 0.0;
    for (size_t k = 0; k < ev.size(); ++k) volume += std::max(0.0, opening[joint[k]]) * area[k];
    row.emplace_back("solid_crack_volume", volume);
    if (spec_.fracture->crack_pressure)
      row.emplace_back("solid_crack_pressure", (*spec_.fracture->crack_pressure)(time));
  }
  if (contact_) {
    const ContactTotals c = contact_->totals();
    row.emplace_back("contact_pairs", static_cast<double>(c.pairs));
    row.emplace_back("contact_touching", static_cast<double>(c.touching));
    row.emplace_back("contact_sliding", static_cast<double>(c.sliding));
    row.emplace_back("contact_energy", e.contact_stored);
    row.emplace_back("contact_friction_dissipation", e.friction);
    row.emplace_back("contact_damping_dissipation", e.contact_damping);
    row.emplace_back("contact_detections", static_cast<double>(c.detections));
  }
  // Support reactions per surface with prescribed motion: minus the force the body exerts on the held
  // components (quasi-static: the inertia of the held nodes is left out). The load a platen applies.
  std::vector<std::string> surfaces;
  std::vector<size_t> slot(velocity_conditions_.size());
  for (size_t i = 0; i < velocity_conditions_.size(); ++i) {
    // A node set is named by its position in the velocity conditions: "nodes<i>".
    const std::string name =
        velocity_conditions_[i].box_min ? "nodes" + std::to_string(i) : velocity_conditions_[i].surface;
    const auto it = std::find(surfaces.begin(), surfaces.end(), name);
    slot[i] = static_cast<size_t>(it - surfaces.begin());
    if (it == surfaces.end()) surfaces.push_back(name);
  }
  reaction_.assign(3 * surfaces.size(), 0.0);
  const Table& nodes = store_.table(solid::node_table);
  const auto held = solid::node::held.read(nodes);
  const auto f = solid::node::f.read(nodes);
  for (size_t i = 0; i < held.size(); ++i)
    if (held[i] >= 0) reaction_[3 * slot[held[i]] + i % 3] -= f[i];
  for (size_t k = 0; k < surfaces.size(); ++k)
    for (int c = 0; c < 3; ++c)
      row.emplace_back("solid_reaction_" + surfaces[k] + "_" + "xyz"[c], reaction_[3 * k + c]);
}

// fractures.csv: one line per broken joint, in the order they broke (joint order within a step).
void SolidModel::write_logs(const std::filesystem::path& dir) const {
  if (!store_.has(solid::joint_table)) return;
  const Table& ev = store_.table(solid::event_table);
  const auto step = solid::event::step.read(ev);
  const auto time = solid::event::time.read(ev);
  const auto joint = solid::event::joint.read(ev);
  const auto mode = solid::event::mode.read(ev);
  const auto c = solid::event::centroid.read(ev);
  const auto n = solid::event::normal.read(ev);
  const auto area = solid::event::area.read(ev);
  const auto tets = solid::joint::tets.read(store_);
  std::string csv = "step,time,joint,tet_a,tet_b,mode,x,y,z,nx,ny,nz,area\n";
  for (size_t r = 0; r < ev.size(); ++r)
    csv += fmt::format("{},{:.17g},{},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n",
                       step[r], time[r], joint[r], tets[2 * joint[r]], tets[2 * joint[r] + 1],
                       mode[r] == 1 ? "tensile" : (mode[r] == 2 ? "shear" : "initial"), c[3 * r],
                       c[3 * r + 1], c[3 * r + 2], n[3 * r], n[3 * r + 1], n[3 * r + 2], area[r]);
  write_text_atomic(dir / "fractures.csv", csv);
}

}  // namespace rift
