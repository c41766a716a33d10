// SolidModel set-up: nodes and tets from the (possibly discontinuous) mesh, materials, boundary
// conditions, force slots, lumped mass and the stable step.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/core/error.hpp"
#include "engine/mesh/mesh_quality.hpp"
#include "engine/scene/output_fields.hpp"
#include "engine/scene/suggest.hpp"
#include "kernels/stable_step.hpp"
#include "kernels/tet_forces.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {

double max_face_area(std::span<const double> x, const int32_t* t) {
  double best = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double* a = &x[3 * t[(k + 1) % 4]];
    const double* b = &x[3 * t[(k + 2) % 4]];
    const double* c = &x[3 * t[(k + 3) % 4]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    best = std::max(best, 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
  }
  return best;
}

// Which regions a list of names (or "all") selects; `key` names the list in errors.
std::vector<bool> select_regions(const TetMesh& mesh, const std::vector<std::string>& names,
                                 const std::string& key) {
  std::vector<bool> applies(std::max<size_t>(mesh.region_names.size(), 1), false);
  for (const auto& r : names) {
    if (r == "all")
      std::fill(applies.begin(), applies.end(), true);
    else if (int32_t i = mesh.region_index(r); i >= 0)
      applies[i] = true;
    else
      throw Error(key + ": the mesh has no region '" + r + "'" + hint(did_you_mean(r, mesh.region_names)) +
                  "; its regions are: " + join_names(mesh.region_names) + " (or use 'all')");
  }
  return applies;
}

}  // namespace

std::vector<uint8_t> SolidModel::fracture_zone(const TetMesh& mesh) const {
  std::vector<uint8_t> zone(mesh.tets.size(), 0);
  if (!spec_.fracture) return zone;
  const FractureSpec& f = *spec_.fracture;
  const auto applies = select_regions(mesh, f.regions, "solid.fracture.regions");
  for (size_t e = 0; e < mesh.tets.size(); ++e) {
    if (!applies[mesh.tet_region.empty() ? 0 : mesh.tet_region[e]]) continue;
    bool inside = true;
    if (f.box_min)
      for (int c = 0; c < 3; ++c) {
        double centroid = 0.0;
        for (int32_t v : mesh.tets[e]) centroid += 0.25 * mesh.nodes[v][c];
        inside = inside && centroid >= (*f.box_min)[c] && centroid <= (*f.box_max)[c];
      }
    zone[e] = inside ? 1 : 0;
  }
  return zone;
}

void SolidModel::build_nodes_and_tets(const DiscontinuousMesh& dm, const TetMesh& mesh) {
  Table& nodes = store_.add_table(solid::node_table);
  namespace node = solid::node;
  for (const auto& c : {node::x0, node::x, node::v, node::f}) c.create(nodes);
  node::mass.create(nodes);
  node::inv_mass.create(nodes);
  node::free.create(nodes);
  node::held.create(nodes);
  node::slots.create(nodes).indexes(IndexTarget::rows_of(solid::slot_table).or_end());
  node::vertex.create(nodes).indexes(IndexTarget::list_of(mesh.nodes.size()));
  nodes.resize(dm.nodes.size());
  std::copy(dm.node_vertex.begin(), dm.node_vertex.end(), node::vertex.in(nodes).begin());
  auto x0 = node::x0.in(nodes);
  for (size_t n = 0; n < dm.nodes.size(); ++n)
    for (int c = 0; c < 3; ++c) x0[3 * n + c] = dm.nodes[n][c];
  std::copy(x0.begin(), x0.end(), node::x.in(nodes).begin());
  std::fill(node::free.in(nodes).begin(), node::free.in(nodes).end(), uint8_t{1});
  std::fill(node::held.in(nodes).begin(), node::held.in(nodes).end(), -1);

  Table& tets = store_.add_table(solid::tet_table);
  solid::tet::nodes.create(tets).indexes(IndexTarget::rows_of(solid::node_table));
  solid::tet::dm_inv.create(tets);
  solid::tet::volume0.create(tets);
  solid::tet::material.create(tets).indexes(IndexTarget::list_of(spec_.materials.size()));
  solid::tet::region.create(tets).indexes(IndexTarget::list_of(mesh.region_names.size()));
  solid::tet::corner_force.create(tets);
  solid::tet::stress.create(tets);
  solid::tet::energy.create(tets);
  solid::tet::viscous_power.create(tets);
  tets.resize(dm.tets.size());
  auto conn = solid::tet::nodes.in(tets);
  auto region = solid::tet::region.in(tets);
  for (size_t e = 0; e < dm.tets.size(); ++e) {
    for (int k = 0; k < 4; ++k) conn[4 * e + k] = dm.tets[e][k];
    region[e] = mesh.tet_region.empty() ? 0 : mesh.tet_region[e];
  }
  const size_t inverted = kernels::tet_prepare(x0, conn, solid::tet::dm_inv.in(tets),
                                               solid::tet::volume0.in(tets), 0, tets.size());
  if (inverted > 0)
    throw Error(
        "mesh: " + std::to_string(inverted) +
        " tetrahedra have zero or negative volume; the mesh reader should have reoriented them, so the "
        "mesh is degenerate. Regenerate it or check the file.");
}

void SolidModel::assign_materials(const TetMesh& mesh) {
  Table& tets = store_.table(solid::tet_table);
  auto material = solid::tet::material.in(tets);
  auto region = solid::tet::region.read(tets);
  std::fill(material.begin(), material.end(), -1);
  for (size_t m = 0; m < spec_.materials.size(); ++m) {
    const auto applies = select_regions(mesh, spec_.materials[m].regions,
                                        "solid.materials[" + std::to_string(m) + "].regions");
    for (size_t e = 0; e < tets.size(); ++e)
      if (material[e] < 0 && applies[region[e]]) material[e] = static_cast<int32_t>(m);
  }
  for (size_t e = 0; e < tets.size(); ++e)
    if (material[e] < 0)
      throw Error("solid.materials: tet " + std::to_string(e) + " in region '" +
                  mesh.region_names[region[e]] +
                  "' has no material; list that region in a material's regions (or use 'all')");
}

void SolidModel::apply_initial_velocity(const TetMesh& mesh) {
  Table& tets = store_.table(solid::tet_table);
  const auto conn = solid::tet::nodes.read(tets);
  const auto region = solid::tet::region.read(tets);
  auto v = solid::node::v.in(store_);
  for (size_t i = 0; i < spec_.initial_velocity.size(); ++i) {
    const InitialVelocitySpec& iv = spec_.initial_velocity[i];
    const auto applies =
        select_regions(mesh, iv.regions, "solid.initial_velocity[" + std::to_string(i) + "].regions");
    for (size_t e = 0; e < tets.size(); ++e)
      if (applies[region[e]])
        for (int k = 0; k < 4; ++k)
          for (int c = 0; c < 3; ++c) v[3 * conn[4 * e + k] + c] = iv.velocity[c];
  }
}

void SolidModel::apply_boundaries(const DiscontinuousMesh& dm, const TetMesh& mesh) {
  Table& nodes = store_.table(solid::node_table);
  auto free = solid::node::free.in(nodes);
  auto held = solid::node::held.in(nodes);
  Table& faces = store_.add_table(solid::face_table);
  solid::face::nodes.create(faces).indexes(IndexTarget::rows_of(solid::node_table));
  solid::face::load.create(faces);
  solid::face::corner_force.create(faces);

  // Orient each loaded triangle outward: find its tet through the face and point away from the fourth node.
  std::map<std::array<int32_t, 3>, std::array<int32_t, 4>> face_tet;
  for (const auto& t : dm.tets)
    for (int k = 0; k < 4; ++k) {
      std::array<int32_t, 3> f{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]};
      std::sort(f.begin(), f.end());
      face_tet[f] = t;
    }

  std::vector<int32_t> face_nodes, face_load;
  for (size_t b = 0; b < spec_.boundaries.size(); ++b) {
    const SolidBoundarySpec& bc = spec_.boundaries[b];
    const std::string key = "solid.boundaries[" + std::to_string(b) + "].surface";
    if (bc.box_min) {  // a node set: fixed or velocity only (the reader checks)
      if (hold_nodes_in_box(bc, static_cast<int32_t>(velocity_conditions_.size())) == 0)
        throw Error("solid.boundaries[" + std::to_string(b) +
                    "].box_min: no solid node lies in the box; check box_min / box_max against the mesh");
      velocity_conditions_.push_back(bc);
      continue;
    }
    const int32_t surface = mesh.surface_index(bc.surface);
    if (surface < 0)
      throw Error(key + ": the mesh has no surface '" + bc.surface + "'" +
                  hint(did_you_mean(bc.surface, mesh.surface_names)) +
                  "; its surfaces are: " + join_names(mesh.surface_names));
    const bool is_velocity =
        bc.kind == SolidBoundarySpec::Kind::fixed || bc.kind == SolidBoundarySpec::Kind::velocity;
    const int32_t index =
        static_cast<int32_t>(is_velocity ? velocity_conditions_.size() : load_conditions_.size());
    (is_velocity ? velocity_conditions_ : load_conditions_).push_back(bc);
    for (size_t t = 0; t < dm.triangles.size(); ++t) {
      if (mesh.triangle_surface[t] != surface) continue;
      const auto& tri = dm.triangles[t];
      if (is_velocity) {
        // Later conditions override earlier ones on shared nodes (edges, corners), component by component.
        for (int32_t n : tri)
          for (int c = 0; c < 3; ++c)
            if (bc.components[c]) {
              free[3 * n + c] = 0;
              held[3 * n + c] = index;
            }
        continue;
      }
      std::array<int32_t, 3> key3 = tri;
      std::sort(key3.begin(), key3.end());
      auto it = face_tet.find(key3);
      if (it == face_tet.end())
        throw Error(key + ": a triangle of surface '" + bc.surface + "' is not a face of any tetrahedron");
      const auto& tet = it->second;
      int32_t apex = tet[0] + tet[1] + tet[2] + tet[3] - tri[0] - tri[1] - tri[2];
      const auto& p0 = dm.nodes[tri[0]];
      const auto& p1 = dm.nodes[tri[1]];
      const auto& p2 = dm.nodes[tri[2]];
      const auto& pa = dm.nodes[apex];
      double a[3], c[3], d[3];
      for (int i = 0; i < 3; ++i) a[i] = p1[i] - p0[i], c[i] = p2[i] - p0[i], d[i] = pa[i] - p0[i];
      const double n[3] = {a[1] * c[2] - a[2] * c[1], a[2] * c[0] - a[0] * c[2], a[0] * c[1] - a[1] * c[0]};
      const bool outward = n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0;
      face_nodes.insert(face_nodes.end(), {tri[0], outward ? tri[1] : tri[2], outward ? tri[2] : tri[1]});
      face_load.push_back(index);
    }
  }
  faces.resize(face_load.size());
  std::copy(face_nodes.begin(), face_nodes.end(), solid::face::nodes.in(faces).begin());
  std::copy(face_load.begin(), face_load.end(), solid::face::load.in(faces).begin());
  solid::face::load.column(store_).indexes(IndexTarget::list_of(load_conditions_.size()));
  solid::node::held.column(store_).indexes(IndexTarget::list_of(velocity_conditions_.size()).or_none());
}

size_t SolidModel::hold_nodes_in_box(const SolidBoundarySpec& bc, int32_t index) {
  Table& nodes = store_.table(solid::node_table);
  const auto x0 = solid::node::x0.read(nodes);
  auto free = solid::node::free.in(nodes);
  auto held = solid::node::held.in(nodes);
  size_t count = 0;
  for (size_t n = 0; n < nodes.size(); ++n) {
    bool inside = true;
    for (int c = 0; c < 3; ++c)
      inside = inside && x0[3 * n + c] >= (*bc.box_min)[c] && x0[3 * n + c] <= (*bc.box_max)[c];
    if (!inside) continue;
    ++count;
    for (int c = 0; c < 3; ++c)
      if (bc.components[c]) free[3 * n + c] = 0, held[3 * n + c] = index;
  }
  return count;
}

namespace {
// Corner k = 6 j + i of the joints as a slot of kernels::ForceSlots's paired source: joint j stores the
// forces on its side-B corners as rows 3 j + 0..2, and side-A corner i reads row 3 j + i negated.
size_t joint_corner_slot(size_t k) {
  const size_t j = k / 6, i = k % 6;
  return 2 * (3 * j + i % 3) + (i < 3 ? 1 : 0);
}
}  // namespace

void SolidModel::build_force_slots() {
  // Each node lists the corner-force slots that act on it: 4 per tet, then 6 per joint, then 3 per loaded
  // face (not the crack faces). The order is fixed here, which fixes the floating-point sum in the node pass;
  // the node pass relies on a node's slots being grouped by source (tets, joints, faces), which this order
  // gives.
  Table& nodes = store_.table(solid::node_table);
  const auto tets = solid::tet::nodes.read(store_);
  const auto joints =
      store_.has(solid::joint_table) ? solid::joint::nodes.read(store_) : std::span<const int32_t>{};
  // The crack faces (from crack_face_begin_ on) get no slots: the surface loads gather the pressed ones
  // into solid_node.crack_force, so the node pass does not read a zero row for every intact joint's face.
  const auto faces = solid::face::nodes.read(store_).first(3 * crack_face_begin_);
  std::vector<int32_t> count(nodes.size() + 1, 0);
  for (auto list : {tets, joints, faces})
    for (int32_t n : list) ++count[n + 1];
  for (size_t n = 0; n < nodes.size(); ++n) count[n + 1] += count[n];
  Table& slots = store_.add_table(solid::slot_table);
  solid::slot.create(slots);
  slots.resize(count.back());
  auto slot = solid::slot.in(slots);
  auto range = solid::node::slots.in(nodes);
  std::vector<int32_t> next(count.begin(), count.end() - 1);
  int32_t first = 0;
  const std::span<const int32_t> sources[3] = {tets, joints, faces};
  for (int src = 0; src < 3; ++src) {
    const auto list = sources[src];
    for (size_t k = 0; k < list.size(); ++k)
      slot[next[list[k]]++] = first + static_cast<int32_t>(src == 1 ? joint_corner_slot(k) : k);
    first += static_cast<int32_t>(list.size());
  }
  solid::slot.column(store_).indexes(
      IndexTarget::list_of(static_cast<size_t>(first)));  // corner slots: tets', then joints', then faces'

  for (size_t n = 0; n < nodes.size(); ++n) {
    range[2 * n] = count[n];
    range[2 * n + 1] = count[n + 1];
  }
}

void SolidModel::compute_mass_and_stable_dt() {
  Table& nodes = store_.table(solid::node_table);
  const Table& tets = store_.table(solid::tet_table);
  const auto conn = solid::tet::nodes.in(tets);
  const auto vol = solid::tet::volume0.in(tets);
  const auto material = solid::tet::material.in(tets);
  auto mass = solid::node::mass.in(nodes);
  for (size_t e = 0; e < tets.size(); ++e) {
    for (int k = 0; k < 4; ++k) mass[conn[4 * e + k]] += spec_.materials[material[e]].density * vol[e] / 4.0;
    energy_floor_ += 1e-12 * spec_.materials[material[e]].young * vol[e];
  }
  auto inv_mass = solid::node::inv_mass.in(nodes);
  for (size_t n = 0; n < nodes.size(); ++n) inv_mass[n] = mass[n] > 0 ? 1.0 / mass[n] : 0.0;

  // Per-material Lame constants and viscous coefficient eta = 2 h beta sqrt(E rho) (femdem.md 1d), with h
  // the material's mean smallest altitude: beta is then the damping fraction at the typical element.
  const auto x0 = solid::node::x0.read(nodes);
  const size_t nm = spec_.materials.size();
  std::vector<double> h_sum(nm, 0.0), density(nm);
  std::vector<size_t> h_count(nm, 0);
  for (size_t e = 0; e < tets.size(); ++e) {
    h_sum[material[e]] += 3.0 * vol[e] / max_face_area(x0, &conn[4 * e]);
    ++h_count[material[e]];
  }
  tet_materials_.resize(nm);
  for (size_t m = 0; m < nm; ++m) {
    const MaterialSpec& s = spec_.materials[m];
    const double lambda = s.young * s.poisson / ((1 + s.poisson) * (1 - 2 * s.poisson));
    const double mu = s.young / (2 * (1 + s.poisson));
    const double h_mean = h_count[m] ? h_sum[m] / h_count[m] : 0.0;
    tet_materials_[m] = {lambda, mu, 2.0 * h_mean * s.damping * std::sqrt(s.young * s.density)};
    density[m] = s.density;
  }
  // The stable step of the tets, and the tet that sets it (named in diagnostics). A tet of the fracture zone
  // has nodes of its own and vibrates at its own highest frequency, which h / c_p overestimates the step of
  // (1.6 x on the wedge scene's mesh: kernels/stable_step.hpp), so it gets its exact step; tets that share
  // nodes keep the estimate, adequate for an assembled mesh (stable at 1.5 x it: docs/stability.md).
  // Each tet's step is kept for mass scaling's per-node bound.
  tet_stable_dt_ = INFINITY;
  tet_steps_.resize(tets.size());
  for (size_t e = 0; e < tets.size(); ++e) {
    const double dt =
        zone_[e] ? kernels::tet_exact_stable_step(x0, conn, material, tet_materials_, density, e, e + 1)
                 : kernels::tet_damped_stable_step(x0, conn, material, tet_materials_, density, e, e + 1);
    tet_steps_[e] = dt;
    if (dt < tet_stable_dt_) tet_stable_dt_ = dt, critical_tet_ = static_cast<int64_t>(e);
  }
  check_step_outlier();
}

// A tet whose step is far below the mesh's median is a sliver or a flat tet, not a feature: it would set
// the step of the whole run (the median tet took 1e4 of its steps for one of its own at 1e-4 of it). Below
// 1e-4 of the median the mesh is refused, below 1e-2 the log says which tet; each message names the tet,
// where it is, its shape and what to change. A 2 degree sliver in an otherwise regular lattice is 36 x
// below its neighbours (docs/stability.md) and passes; the 1e-14 radius-ratio tet of a badly meshed disc
// is 1e27 x below and is refused.
void SolidModel::check_step_outlier() const {
  if (tet_steps_.empty() || critical_tet_ < 0) return;
  std::vector<double> steps(tet_steps_);
  const auto mid = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), mid, steps.end());
  const double median = *mid, ratio = tet_stable_dt_ / median;
  if (!(ratio < 1e-2)) return;
  const auto x0 = solid::node::x0.read(store_);
  const auto conn = solid::tet::nodes.read(store_);
  const auto e = static_cast<size_t>(critical_tet_);
  std::array<double, 3> c[4];
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) c[k][i] = x0[3 * static_cast<size_t>(conn[4 * e + k]) + i];
  const TetShape shape = tet_shape(c[0], c[1], c[2], c[3]);
  const std::string what = fmt::format(
      "tet {} at ({:.6g}, {:.6g}, {:.6g}) m has a stable step of {:.3g} s, {:.3g} x the mesh's median "
      "({:.3g} s): dihedral angles {:.3g} .. {:.4g} deg, radius ratio {:.3g}, edges {:.3g} .. {:.3g} m",
      e, 0.25 * (c[0][0] + c[1][0] + c[2][0] + c[3][0]), 0.25 * (c[0][1] + c[1][1] + c[2][1] + c[3][1]),
      0.25 * (c[0][2] + c[1][2] + c[2][2] + c[3][2]), tet_stable_dt_, ratio, median,
      shape.min_dihedral_rad * 180 / M_PI, shape.max_dihedral_rad * 180 / M_PI, shape.radius_ratio,
      shape.min_edge, shape.max_edge);
  if (ratio < 1e-4)
    throw Error("mesh: " + what +
                ", a sliver or flat tet that would set the step of the whole run. What to change: regenerate "
                "the mesh (another mesh.generate.size_min, or Gmsh's Optimize) or remove that element");
  spdlog::warn("mesh: {}; it sets the run's step. A better-shaped mesh there would take fewer steps", what);
}

}  // namespace rift
