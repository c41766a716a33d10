#include "systems/solid_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "engine/core/error.hpp"
#include "kernels/stable_step.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none)" : out;
}

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

bool wants(const std::vector<std::string>& fields, const char* name) {
  return fields.empty() || std::find(fields.begin(), fields.end(), name) != fields.end();
}

}  // namespace

SolidModel::SolidModel(Store& store, const TetMesh& mesh, const SolidSpec& spec)
    : store_(store), spec_(spec) {
  build_nodes_and_tets(mesh);
  assign_materials(mesh);
  apply_boundaries(mesh);
  build_force_slots();
  compute_mass_and_stable_dt();
  loads_ = std::make_unique<SurfaceLoadSystem>(store_, load_conditions_);
  tet_forces_ = std::make_unique<TetForceSystem>(store_, tet_materials_);
  integration_ = std::make_unique<NodeIntegrationSystem>(store_, velocity_conditions_, spec_.gravity);
}

std::vector<System*> SolidModel::systems() {
  return {loads_.get(), tet_forces_.get(), integration_.get()};
}

void SolidModel::build_nodes_and_tets(const TetMesh& mesh) {
  Table& nodes = store_.add_table(solid::node_table);
  nodes.add<double>("x0", 3);
  nodes.add<double>("x", 3);
  nodes.add<double>("v", 3);
  nodes.add<double>("f", 3);
  nodes.add<double>("mass");
  nodes.add<double>("inv_mass");
  nodes.add<uint8_t>("free", 3);
  nodes.add<int32_t>("held");
  nodes.add<int32_t>("slots", 2);
  nodes.resize(mesh.nodes.size());
  auto x0 = nodes.span<double>("x0");
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int c = 0; c < 3; ++c) x0[3 * n + c] = mesh.nodes[n][c];
  std::copy(x0.begin(), x0.end(), nodes.span<double>("x").begin());
  std::fill(nodes.span<uint8_t>("free").begin(), nodes.span<uint8_t>("free").end(), uint8_t{1});
  std::fill(nodes.span<int32_t>("held").begin(), nodes.span<int32_t>("held").end(), -1);

  Table& tets = store_.add_table(solid::tet_table);
  tets.add<int32_t>("nodes", 4);
  tets.add<double>("dm_inv", 9);
  tets.add<double>("volume0");
  tets.add<int32_t>("material");
  tets.add<int32_t>("region");
  tets.add<double>("corner_force", 12);
  tets.add<double>("stress", 6);
  tets.add<double>("energy");
  tets.resize(mesh.tets.size());
  auto conn = tets.span<int32_t>("nodes");
  auto region = tets.span<int32_t>("region");
  for (size_t e = 0; e < mesh.tets.size(); ++e) {
    for (int k = 0; k < 4; ++k) conn[4 * e + k] = mesh.tets[e][k];
    region[e] = mesh.tet_region.empty() ? 0 : mesh.tet_region[e];
  }
  const size_t inverted = kernels::tet_prepare(x0, conn, tets.span<double>("dm_inv"),
                                               tets.span<double>("volume0"), 0, tets.size());
  if (inverted > 0)
    throw Error(
        "mesh: " + std::to_string(inverted) +
        " tetrahedra have zero or negative volume; the mesh reader should have reoriented them, so the "
        "mesh is degenerate. Regenerate it or check the file.");
}

void SolidModel::assign_materials(const TetMesh& mesh) {
  Table& tets = store_.table(solid::tet_table);
  auto material = tets.span<int32_t>("material");
  auto region = tets.span<const int32_t>("region");
  std::fill(material.begin(), material.end(), -1);
  for (size_t m = 0; m < spec_.materials.size(); ++m) {
    const MaterialSpec& s = spec_.materials[m];
    std::vector<bool> applies(std::max<size_t>(mesh.region_names.size(), 1), false);
    for (const auto& r : s.regions) {
      if (r == "all")
        std::fill(applies.begin(), applies.end(), true);
      else if (int32_t i = mesh.region_index(r); i >= 0)
        applies[i] = true;
      else
        throw Error("solid.materials[" + std::to_string(m) + "].regions: the mesh has no region '" + r +
                    "'; its regions are: " + join(mesh.region_names) + " (or use 'all')");
    }
    for (size_t e = 0; e < tets.size(); ++e)
      if (material[e] < 0 && applies[region[e]]) material[e] = static_cast<int32_t>(m);
  }
  for (size_t e = 0; e < tets.size(); ++e)
    if (material[e] < 0)
      throw Error("solid.materials: tet " + std::to_string(e) + " in region '" +
                  mesh.region_names[region[e]] +
                  "' has no material; list that region in a material's regions (or use 'all')");
}

void SolidModel::apply_boundaries(const TetMesh& mesh) {
  Table& nodes = store_.table(solid::node_table);
  auto free = nodes.span<uint8_t>("free");
  auto held = nodes.span<int32_t>("held");
  Table& faces = store_.add_table(solid::face_table);
  faces.add<int32_t>("nodes", 3);
  faces.add<int32_t>("load");
  faces.add<double>("corner_force", 9);

  // Orient each loaded triangle outward: find its tet through the face and point away from the fourth node.
  std::map<std::array<int32_t, 3>, std::array<int32_t, 4>> face_tet;
  for (const auto& t : mesh.tets)
    for (int k = 0; k < 4; ++k) {
      std::array<int32_t, 3> f{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]};
      std::sort(f.begin(), f.end());
      face_tet[f] = t;
    }

  std::vector<int32_t> face_nodes, face_load;
  for (size_t b = 0; b < spec_.boundaries.size(); ++b) {
    const SolidBoundarySpec& bc = spec_.boundaries[b];
    const std::string key = "solid.boundaries[" + std::to_string(b) + "].surface";
    const int32_t surface = mesh.surface_index(bc.surface);
    if (surface < 0)
      throw Error(key + ": the mesh has no surface '" + bc.surface +
                  "'; its surfaces are: " + join(mesh.surface_names));
    const bool is_velocity =
        bc.kind == SolidBoundarySpec::Kind::fixed || bc.kind == SolidBoundarySpec::Kind::velocity;
    const int32_t index =
        static_cast<int32_t>(is_velocity ? velocity_conditions_.size() : load_conditions_.size());
    (is_velocity ? velocity_conditions_ : load_conditions_).push_back(bc);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (mesh.triangle_surface[t] != surface) continue;
      const auto& tri = mesh.triangles[t];
      if (is_velocity) {
        // Later conditions override earlier ones on shared nodes (edges, corners), component by component.
        for (int32_t n : tri)
          for (int c = 0; c < 3; ++c)
            if (bc.components[c]) {
              free[3 * n + c] = 0;
              held[n] = index;
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
      const auto& p0 = mesh.nodes[tri[0]];
      const auto& p1 = mesh.nodes[tri[1]];
      const auto& p2 = mesh.nodes[tri[2]];
      const auto& pa = mesh.nodes[apex];
      double a[3], c[3], d[3];
      for (int i = 0; i < 3; ++i) a[i] = p1[i] - p0[i], c[i] = p2[i] - p0[i], d[i] = pa[i] - p0[i];
      const double n[3] = {a[1] * c[2] - a[2] * c[1], a[2] * c[0] - a[0] * c[2], a[0] * c[1] - a[1] * c[0]};
      const bool outward = n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0;
      face_nodes.insert(face_nodes.end(), {tri[0], outward ? tri[1] : tri[2], outward ? tri[2] : tri[1]});
      face_load.push_back(index);
    }
  }
  faces.resize(face_load.size());
  std::copy(face_nodes.begin(), face_nodes.end(), faces.span<int32_t>("nodes").begin());
  std::copy(face_load.begin(), face_load.end(), faces.span<int32_t>("load").begin());
}

void SolidModel::build_force_slots() {
  // Each node lists the corner-force slots that act on it: 4 per tet, then 3 per loaded face. The order
  // (tets by index, then faces) is fixed here, which fixes the floating-point sum in the node pass.
  Table& nodes = store_.table(solid::node_table);
  const auto tets = store_.table(solid::tet_table).span<const int32_t>("nodes");
  const auto faces = store_.table(solid::face_table).span<const int32_t>("nodes");
  std::vector<int32_t> count(nodes.size() + 1, 0);
  for (int32_t n : tets) ++count[n + 1];
  for (int32_t n : faces) ++count[n + 1];
  for (size_t n = 0; n < nodes.size(); ++n) count[n + 1] += count[n];
  Table& slots = store_.add_table(solid::slot_table);
  slots.add<int32_t>("slot");
  slots.resize(count.back());
  auto slot = slots.span<int32_t>("slot");
  auto range = nodes.span<int32_t>("slots");
  std::vector<int32_t> next(count.begin(), count.end() - 1);
  for (size_t k = 0; k < tets.size(); ++k) slot[next[tets[k]]++] = static_cast<int32_t>(k);
  const int32_t split = static_cast<int32_t>(tets.size());
  for (size_t k = 0; k < faces.size(); ++k) slot[next[faces[k]]++] = split + static_cast<int32_t>(k);
  for (size_t n = 0; n < nodes.size(); ++n) {
    range[2 * n] = count[n];
    range[2 * n + 1] = count[n + 1];
  }
}

void SolidModel::compute_mass_and_stable_dt() {
  Table& nodes = store_.table(solid::node_table);
  const Table& tets = store_.table(solid::tet_table);
  const auto conn = tets.span<int32_t>("nodes");
  const auto vol = tets.span<double>("volume0");
  const auto material = tets.span<int32_t>("material");
  auto mass = nodes.span<double>("mass");
  for (size_t e = 0; e < tets.size(); ++e)
    for (int k = 0; k < 4; ++k) mass[conn[4 * e + k]] += spec_.materials[material[e]].density * vol[e] / 4.0;
  auto inv_mass = nodes.span<double>("inv_mass");
  for (size_t n = 0; n < nodes.size(); ++n) inv_mass[n] = mass[n] > 0 ? 1.0 / mass[n] : 0.0;

  // Per-material Lame constants and viscous coefficient eta = 2 h beta sqrt(E rho) (femdem.md 1d), with h
  // the material's mean smallest altitude: beta is then the damping fraction at the typical element.
  const auto x0 = nodes.span<const double>("x0");
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
  // The stable step, and the tet that sets it (named in diagnostics).
  stable_dt_ = INFINITY;
  for (size_t e = 0; e < tets.size(); ++e) {
    const double dt = kernels::tet_damped_stable_step(x0, conn, material, tet_materials_, density, e, e + 1);
    if (dt < stable_dt_) stable_dt_ = dt, critical_tet_ = static_cast<int64_t>(e);
  }
}

std::optional<std::string> SolidModel::check_health(const StepContext& after) {
  std::ostringstream why;
  if (tet_forces_->inverted() > 0) {
    const int64_t e = tet_forces_->first_inverted();
    const auto conn = store_.table(solid::tet_table).span<const int32_t>("nodes");
    const auto x = store_.table(solid::node_table).span<const double>("x");
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) c[i] += 0.25 * x[3 * conn[4 * e + k] + i];
    why << tet_forces_->inverted() << " tetrahedra inverted (J <= 0) at step " << after.step
        << ", t = " << after.time << " s; first: tet " << e << " at (" << c[0] << ", " << c[1] << ", " << c[2]
        << ") m. Likely cause: a load "
        << "too large or too sudden for the element (or a dt above the stable step). What to change: lower "
           "the load "
        << "or its rate, refine the mesh there, or reduce time.dt / time.safety.";
    return why.str();
  }
  if (integration_->non_finite_nodes() > 0) {
    why << integration_->non_finite_nodes() << " solid nodes have a non-finite position or velocity at step "
        << after.step << ", t = " << after.time << " s. Likely cause: dt above the stable step ("
        << stable_dt_ << " s, set by tet " << critical_tet_
        << ") or a load that grows without bound. What to change: reduce "
        << "time.dt or time.safety, check loads and materials.";
    return why.str();
  }
  return std::nullopt;
}

void SolidModel::output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {
  const Table& nodes = store_.table(solid::node_table);
  const Table& tets = store_.table(solid::tet_table);
  const auto x = nodes.span<double>("x");
  const auto x0 = nodes.span<double>("x0");
  displacement_.resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) displacement_[i] = x[i] - x0[i];
  const auto stress = tets.span<double>("stress");
  principal_.resize(3 * tets.size());
  for (size_t e = 0; e < tets.size(); ++e) principal_values(&stress[6 * e], &principal_[3 * e]);

  XdmfGrid g;
  g.name = "solid";
  g.topology = Topology::tetrahedron;
  g.points = x.data();
  g.point_count = nodes.size();
  g.cells = tets.span<int32_t>("nodes").data();
  g.cell_count = tets.size();
  g.mesh_revision = 0;
  g.points_move = true;
  auto node_field = [&](const char* name, const double* data) {
    if (wants(fields, name))
      g.fields.push_back({name, Center::node, 3, ElementType::f64, data, nodes.size()});
  };
  node_field("displacement", displacement_.data());
  node_field("velocity", nodes.span<double>("v").data());
  node_field("force", nodes.span<double>("f").data());
  if (wants(fields, "stress"))
    g.fields.push_back({"stress", Center::cell, 6, ElementType::f64, stress.data(), tets.size()});
  if (wants(fields, "principal_stress"))
    g.fields.push_back(
        {"principal_stress", Center::cell, 3, ElementType::f64, principal_.data(), tets.size()});
  if (wants(fields, "region"))
    g.fields.push_back(
        {"region", Center::cell, 1, ElementType::i32, tets.span<int32_t>("region").data(), tets.size()});
  if (wants(fields, "material"))
    g.fields.push_back(
        {"material", Center::cell, 1, ElementType::i32, tets.span<int32_t>("material").data(), tets.size()});
  grids.push_back(std::move(g));
}

void SolidModel::metrics(double time, std::vector<std::pair<std::string, double>>& row) {
  const Table& nodes = store_.table(solid::node_table);
  const auto v = nodes.span<const double>("v");
  const auto m = nodes.span<const double>("mass");
  double kinetic = 0.0;
  for (size_t n = 0; n < nodes.size(); ++n)
    kinetic += 0.5 * m[n] * (v[3 * n] * v[3 * n] + v[3 * n + 1] * v[3 * n + 1] + v[3 * n + 2] * v[3 * n + 2]);
  double elastic = 0.0;
  for (double w : store_.table(solid::tet_table).span<const double>("energy")) elastic += w;
  row.emplace_back("solid_kinetic_energy", kinetic);
  row.emplace_back("solid_elastic_energy", elastic);
}

void SolidModel::summarize(nlohmann::json& summary) const {
  summary["solid"]["nodes"] = store_.table(solid::node_table).size();
  summary["solid"]["tets"] = store_.table(solid::tet_table).size();
  summary["solid"]["loaded_faces"] = store_.table(solid::face_table).size();
  summary["solid"]["stable_dt"] = stable_dt_;
  summary["solid"]["critical_tet"] = critical_tet_;
}

}  // namespace rift
