#include "systems/fracture_flow/fracture_flow_model.hpp"

#include <algorithm>
#include <array>
#include <map>

#include "engine/core/error.hpp"
#include "engine/scene/output_fields.hpp"
#include "systems/fracture_flow/fracture_flow_tables.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

namespace {
// 1 per mesh vertex: on one of the vent surfaces (every surface of the mesh when none is named). A
// plane-strain slab names its open faces, so that the faces that close the slab do not vent.
std::vector<uint8_t> vent_vertices(const TetMesh& mesh, const std::vector<std::string>& names) {
  std::vector<uint8_t> chosen(mesh.surface_names.size(), names.empty() ? 1 : 0);
  for (const auto& name : names) {
    const auto it = std::find(mesh.surface_names.begin(), mesh.surface_names.end(), name);
    if (it == mesh.surface_names.end()) {
      std::string known;
      for (const auto& s : mesh.surface_names) known += (known.empty() ? "" : ", ") + s;
      throw Error("fracture_flow.vent_surfaces: no surface '" + name + "' in the mesh (it has: " + known +
                  ")");
    }
    chosen[size_t(it - mesh.surface_names.begin())] = 1;
  }
  std::vector<uint8_t> on(mesh.nodes.size(), 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    if (chosen[size_t(mesh.triangle_surface[t])])
      for (int32_t v : mesh.triangles[t]) on[size_t(v)] = 1;
  return on;
}

// The well's wall (fracture_flow.injection.surfaces): the faces of the named surfaces as solid node
// triples whose normal points out of the rock (each boundary triangle is the face of one tet; its fourth
// node is inside), and the mesh vertices on them.
WellWall well_wall(const Store& store, const TetMesh& mesh, const std::vector<std::string>& names) {
  WellWall wall;
  if (names.empty()) return wall;
  std::vector<uint8_t> chosen(mesh.surface_names.size(), 0);
  for (const auto& name : names) {
    const auto it = std::find(mesh.surface_names.begin(), mesh.surface_names.end(), name);
    if (it == mesh.surface_names.end()) {
      std::string known;
      for (const auto& s : mesh.surface_names) known += (known.empty() ? "" : ", ") + s;
      throw Error("fracture_flow.injection.surfaces: no surface '" + name +
                  "' in the mesh (it has: " + known + ")");
    }
    chosen[size_t(it - mesh.surface_names.begin())] = 1;
  }
  const Table& nodes = store.table(solid::node_table);
  const auto node_vertex = solid::node::vertex.read(nodes);
  const auto x0 = solid::node::x0.read(nodes);
  const auto tet_nodes = solid::tet::nodes.read(store);
  std::map<std::array<int32_t, 3>, std::pair<size_t, int>> face_of;  // sorted mesh vertices -> tet, corner
  for (size_t t = 0; 4 * t < tet_nodes.size(); ++t)
    for (int k = 0; k < 4; ++k) {
      std::array<int32_t, 3> f{};
      for (int c = 0; c < 3; ++c)
        f[size_t(c)] = node_vertex[size_t(tet_nodes[4 * t + size_t((k + 1 + c) % 4)])];
      std::sort(f.begin(), f.end());
      face_of[f] = {t, k};
    }
  wall.on_wall.assign(mesh.nodes.size(), 0);
  for (size_t tri = 0; tri < mesh.triangles.size(); ++tri) {
    if (!chosen[size_t(mesh.triangle_surface[tri])]) continue;
    std::array<int32_t, 3> f = mesh.triangles[tri];
    for (int32_t v : f) wall.on_wall[size_t(v)] = 1;
    std::sort(f.begin(), f.end());
    const auto it = face_of.find(f);
    if (it == face_of.end())
      throw Error(
          "fracture_flow.injection.surfaces: a triangle of the wall is not a face of any tetrahedron");
    const auto [t, k] = it->second;
    int32_t corner[3], apex = tet_nodes[4 * t + size_t(k)];
    for (int c = 0; c < 3; ++c) corner[c] = tet_nodes[4 * t + size_t((k + 1 + c) % 4)];
    auto at = [&](int32_t n, int d) { return x0[3 * size_t(n) + size_t(d)]; };
    double u[3], w[3], a[3];
    for (int d = 0; d < 3; ++d)
      u[d] = at(corner[1], d) - at(corner[0], d), w[d] = at(corner[2], d) - at(corner[0], d),
      a[d] = at(apex, d) - at(corner[0], d);
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    if (n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0) std::swap(corner[1], corner[2]);
    wall.face_nodes.insert(wall.face_nodes.end(), corner, corner + 3);
  }
  return wall;
}

}  // namespace

FractureFlowModel::FractureFlowModel(Store& store, SolidModel& solid, const TetMesh& mesh,
                                     const FractureFlowSpec& spec)
    : store_(store), spec_(spec) {
  solid.accept_crack_fluid_forces();
  system_ = std::make_unique<FractureFlowSystem>(store, spec, solid.spec().mass_damping,
                                                 vent_vertices(mesh, spec.vent_surfaces),
                                                 well_wall(store, mesh, spec.well_surfaces));
}

std::optional<std::string> FractureFlowModel::check_health(const StepContext&) {
  if (system_->problem().empty()) return std::nullopt;
  return system_->problem();
}

void FractureFlowModel::metrics(double, std::vector<std::pair<std::string, double>>& row) {
  const FractureFlowSystem::Measures m = system_->measure();
  const Table& books = store_.table(fracture_flow::books_table);
  auto book = [&](const char* c) { return books.span<const double>(c)[0]; };
  const double injected_volume = book("injected") / spec_.eos.density0;
  row.emplace_back("flow_well_pressure", m.well_pressure);
  row.emplace_back("flow_injected_volume", injected_volume);
  row.emplace_back("flow_fluid_volume", m.fluid_volume);
  row.emplace_back("flow_crack_volume", m.crack_volume);
  row.emplace_back("flow_vented_volume", book("vented") / spec_.eos.density0);
  row.emplace_back("flow_leaked_volume", book("leaked") / spec_.eos.density0);
  row.emplace_back("flow_crack_area", m.crack_area);
  row.emplace_back("flow_wet_area", m.wet_area);
  row.emplace_back("flow_crack_extent", m.crack_extent);
  row.emplace_back("flow_front_extent", m.front_extent);
  // Efficiency: the share of the injected fluid that is still in the crack (the rest leaked or vented).
  row.emplace_back("flow_efficiency", injected_volume > 0 ? m.crack_volume / injected_volume : 0.0);
  const double mass = system_->total_mass();
  row.emplace_back("flow_mass_error",
                   mass - (book("initial_mass") + book("injected") - book("vented") - book("leaked")));
  // Energy: the pump's work goes into the rock (fluid_work), viscous dissipation and compression.
  row.emplace_back("flow_pump_work", book("pump_work"));
  row.emplace_back("flow_work_on_solid", book("fluid_work"));
  row.emplace_back("flow_dissipation", book("dissipation"));
  row.emplace_back("flow_compression_energy", m.compression_energy);
}

void FractureFlowModel::output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {
  system_->network_geometry(points_, triangles_, rows_, point_aperture_);
  const Table& rows = store_.table(fracture_flow::vertex_table);
  const auto pressure = fracture_flow::vertex::pressure.read(rows);
  const auto wetting = fracture_flow::vertex::wetting_time.read(rows);
  const size_t n = rows_.size();
  point_pressure_.resize(n);
  point_wetting_.resize(n);
  for (size_t v = 0; v < n; ++v) {
    point_pressure_[v] = pressure[size_t(rows_[v])];
    point_wetting_[v] = wetting[size_t(rows_[v])];
  }
  XdmfGrid g{"crack_network",
             Topology::triangle,
             points_.data(),
             n,
             triangles_.data(),
             triangles_.size() / 3,
             uint64_t(triangles_.size() / 3),
             true,
             {}};
  if (wants_field(fields, "pressure"))
    g.fields.push_back({"pressure", Center::node, 1, ElementType::f64, point_pressure_.data(), n});
  if (wants_field(fields, "aperture"))
    g.fields.push_back({"aperture", Center::node, 1, ElementType::f64, point_aperture_.data(), n});
  if (wants_field(fields, "wetting_time"))
    g.fields.push_back({"wetting_time", Center::node, 1, ElementType::f64, point_wetting_.data(), n});
  grids.push_back(std::move(g));
}

void FractureFlowModel::summarize(nlohmann::json& summary) const {
  const FractureFlowSystem::Measures m = system_->measure();
  const Table& books = store_.table(fracture_flow::books_table);
  auto book = [&](const char* c) { return books.span<const double>(c)[0]; };
  summary["fracture_flow"] = {
      {"well_pressure", m.well_pressure},    {"injected_volume", book("injected") / spec_.eos.density0},
      {"crack_volume", m.crack_volume},      {"fluid_volume", m.fluid_volume},
      {"crack_area", m.crack_area},          {"wet_area", m.wet_area},
      {"crack_extent", m.crack_extent},      {"front_extent", m.front_extent},
      {"network_triangles", m.triangles},    {"pump_work", book("pump_work")},
      {"work_on_solid", book("fluid_work")}, {"dissipation", book("dissipation")}};
}

// Every solid node belongs to one tet (FEMDEM): a wall face's tet is its first corner's.
std::vector<int32_t> FractureFlowModel::well_wall_tets() const {
  const auto tet_nodes = solid::tet::nodes.read(store_);
  std::vector<int32_t> tet_of_node(store_.table(solid::node_table).size(), -1);
  for (size_t i = 0; i < tet_nodes.size(); ++i) tet_of_node[size_t(tet_nodes[i])] = int32_t(i / 4);
  const auto& faces = system_->well_wall().face_nodes;
  std::vector<int32_t> tets;
  for (size_t f = 0; f < faces.size(); f += 3) tets.push_back(tet_of_node[size_t(faces[f])]);
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  return tets;
}

}  // namespace rift
