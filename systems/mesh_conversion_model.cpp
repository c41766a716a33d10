#include "systems/mesh_conversion_model.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "systems/solid_tables.hpp"

namespace rift {

MeshConversionModel::MeshConversionModel(Store& store, const TetMesh& mesh,
                                         const std::vector<std::string>& notch_surfaces)
    : store_(store) {
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    if (std::find(notch_surfaces.begin(), notch_surfaces.end(),
                  mesh.surface_names[mesh.triangle_surface[t]]) != notch_surfaces.end())
      notch_triangles_.push_back(mesh.triangles[t]);
  SolidTopology topology;
  topology.input_vertex_count = mesh.nodes.size();
  topology.node_vertex = solid::node::vertex.read(store_);
  topology.tet_nodes = solid::tet::nodes.read(store_);
  if (store_.has(solid::joint_table)) {
    topology.joint_nodes = solid::joint::nodes.read(store_);
    topology.joint_tets = solid::joint::tets.read(store_);
  }
  topology.notch_triangles = notch_triangles_;
  conversion_ = std::make_unique<MeshConversion>(topology);
  if (store_.has(solid::joint_table)) system_ = std::make_unique<MeshConversionSystem>(store_, *conversion_);
  spdlog::info("mesh conversion: {} continuous vertices, {} surface triangles ({} on notches)",
               conversion_->vertex_count(), conversion_->triangle_count(), notch_triangles_.size());
}

const MeshConversion& MeshConversionModel::conversion() {
  if (system_) system_->catch_up();
  return *conversion_;
}

void MeshConversionModel::update_kinematics() {
  conversion();
  const Table& nodes = store_.table(solid::node_table);
  conversion_->update_kinematics(solid::node::x.read(nodes), solid::node::v.read(nodes),
                                 solid::node::mass.read(nodes));
}

void MeshConversionModel::output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {
  update_kinematics();
  const MeshConversion& c = *conversion_;
  tag_.resize(c.triangle_count());
  std::transform(c.triangle_tag().begin(), c.triangle_tag().end(), tag_.begin(),
                 [](SurfaceTag t) { return static_cast<uint8_t>(t); });
  // Connectivity changes only when a joint breaks: the revision is the number of breaks, a function of
  // the state, so a restarted run numbers its surface meshes as the uninterrupted one did.
  XdmfGrid g{"surface",
             Topology::triangle,
             c.vertex_x().data(),
             c.vertex_count(),
             c.triangle_vertices().data(),
             c.triangle_count(),
             c.revision(),
             true,
             {}};
  auto wants = [&](const char* name) {
    return fields.empty() || std::find(fields.begin(), fields.end(), name) != fields.end();
  };
  if (wants("velocity"))
    g.fields.push_back(
        {"velocity", Center::node, 3, ElementType::f64, c.vertex_v().data(), c.vertex_count()});
  // Always written: they say what each triangle is (tag 0 boundary, 1 notch, 2 fracture).
  g.fields.push_back({"tag", Center::cell, 1, ElementType::u8, tag_.data(), c.triangle_count()});
  g.fields.push_back(
      {"fracture_time", Center::cell, 1, ElementType::f64, c.triangle_time().data(), c.triangle_count()});
  g.fields.push_back(
      {"joint", Center::cell, 1, ElementType::i32, c.triangle_joint().data(), c.triangle_count()});
  grids.push_back(std::move(g));
}

void MeshConversionModel::metrics(double time, std::vector<std::pair<std::string, double>>& row) {
  const MeshConversion& c = conversion();
  row.emplace_back("conversion_vertices", static_cast<double>(c.vertex_count()));
  row.emplace_back("conversion_surface_triangles", static_cast<double>(c.triangle_count()));
}

void MeshConversionModel::summarize(nlohmann::json& summary) const {
  if (system_) system_->catch_up();
  const MeshConversion& c = *conversion_;
  auto& s = summary["mesh_conversion"];
  s["vertices"] = c.vertex_count();
  s["surface_triangles"] = c.triangle_count();
  s["external_triangles"] = c.external_triangle_count();
  s["fracture_triangles"] = c.triangle_count() - c.external_triangle_count();
  s["fracture_surfaces"] = c.fracture_surface_count();
  s["fragments"] = c.fragment_count();
}

}  // namespace rift
