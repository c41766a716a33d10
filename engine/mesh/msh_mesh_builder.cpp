#include "engine/mesh/msh_mesh_builder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "engine/core/error.hpp"

namespace rift {
namespace {

// Physical tags of one dimension, in tag order, with their names.
std::vector<std::pair<int, std::string>> physical_groups(
    int dim, const std::map<std::pair<int, int>, std::string>& names,
    const std::unordered_map<int, std::vector<int>>& entity_physicals) {
  std::set<int> tags;
  for (const auto& [key, name] : names)
    if (key.first == dim) tags.insert(key.second);
  for (const auto& [entity, physicals] : entity_physicals) tags.insert(physicals.begin(), physicals.end());
  std::vector<std::pair<int, std::string>> groups;
  for (const int tag : tags) {
    const auto it = names.find({dim, tag});
    groups.emplace_back(
        tag, it != names.end() ? it->second : (dim == 3 ? "volume_" : "surface_") + std::to_string(tag));
  }
  return groups;
}

// Physical tag -> index into `groups`.
std::unordered_map<int, int32_t> index_by_tag(const std::vector<std::pair<int, std::string>>& groups) {
  std::unordered_map<int, int32_t> index;
  index.reserve(groups.size());
  for (size_t i = 0; i < groups.size(); ++i) index.emplace(groups[i].first, static_cast<int32_t>(i));
  return index;
}

}  // namespace

void MshNodeTags::reserve(int64_t max_tag, int64_t count) {
  if (max_tag >= 0 && max_tag <= 4 * count + 1024)
    dense_.assign(static_cast<size_t>(max_tag) + 1, -1);
  else
    sparse_.reserve(static_cast<size_t>(count));
}

bool MshNodeTags::insert(int64_t tag, int32_t index) {
  if (tag >= 0 && static_cast<size_t>(tag) < dense_.size()) {
    if (dense_[tag] >= 0) return false;
    dense_[tag] = index;
    return true;
  }
  return sparse_.emplace(tag, index).second;
}

void MshMeshBuilder::set_entity_groups(int dim, int entity, std::vector<int> physicals) {
  if ((dim == 2 || dim == 3) && !physicals.empty()) entity_physicals_[dim - 2][entity] = std::move(physicals);
}

bool MshMeshBuilder::has_entity_groups(int dim, int entity) const {
  return (dim == 2 || dim == 3) && entity_physicals_[dim - 2].count(entity) > 0;
}

void MshMeshBuilder::reserve_nodes(int64_t max_tag, int64_t count) {
  node_index_.reserve(max_tag, count);
  nodes_.reserve(static_cast<size_t>(count));
  node_tag_.reserve(static_cast<size_t>(count));
  node_position_.reserve(static_cast<size_t>(count));
}

void MshMeshBuilder::add_node(int64_t tag, const Vec3& x, uint64_t position) {
  if (nodes_.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    f_->fail("at most 2^31 - 1 nodes", "more");
  if (!node_index_.insert(tag, static_cast<int32_t>(nodes_.size())))
    f_->fail("node tags to be unique", "node tag " + std::to_string(tag) + " a second time");
  nodes_.push_back({x[0] * scale_, x[1] * scale_, x[2] * scale_});
  node_tag_.push_back(tag);
  node_position_.push_back(position);
}

int32_t MshMeshBuilder::node_index(int64_t node_tag, int64_t element_tag, uint64_t position) const {
  const int32_t v = node_index_.find(node_tag);
  if (v < 0)
    f_->fail_at(position, "a node tag defined in $Nodes",
                std::to_string(node_tag) + " in element " + std::to_string(element_tag));
  return v;
}

void MshMeshBuilder::add_tet(int64_t tag, const int64_t (&node_tags)[4], int entity, uint64_t position) {
  std::array<int32_t, 4> tet;
  for (int k = 0; k < 4; ++k) tet[k] = node_index(node_tags[k], tag, position);
  const Vec3 &x0 = nodes_[tet[0]], &x1 = nodes_[tet[1]], &x2 = nodes_[tet[2]], &x3 = nodes_[tet[3]];
  const Vec3 e1 = sub(x1, x0), e2 = sub(x2, x0), e3 = sub(x3, x0);
  const double six_v = dot(e1, cross(e2, e3));
  double h2 = std::max({dot(e1, e1), dot(e2, e2), dot(e3, e3)});
  h2 = std::max(
      {h2, dot(sub(x2, x1), sub(x2, x1)), dot(sub(x3, x1), sub(x3, x1)), dot(sub(x3, x2), sub(x3, x2))});
  // Relative threshold: |6V| / h^3 is 0.47 for a regular tet; 1e-14 is round-off of a flat one.
  if (!(std::abs(six_v) >= 1e-14 * h2 * std::sqrt(h2)))
    f_->fail_at(
        position, "a tetrahedron with non-zero volume",
        fmt::format("element {} with 6V = {:.3g} for longest edge {:.6g}", tag, six_v, std::sqrt(h2)));
  if (six_v < 0) {
    std::swap(tet[1], tet[2]);
    ++flipped_;
  }
  tets_.push_back(tet);
  tet_entity_.push_back(entity);
  tet_tag_.push_back(tag);
  tet_position_.push_back(position);
}

void MshMeshBuilder::add_triangle(int64_t tag, const int64_t (&node_tags)[3], int entity, uint64_t position) {
  std::array<int32_t, 3> tri;
  for (int k = 0; k < 3; ++k) tri[k] = node_index(node_tags[k], tag, position);
  triangles_.push_back(tri);
  triangle_entity_.push_back(entity);
}

// A tet listed twice (the same four nodes in any order) would count its volume and mass twice.
void MshMeshBuilder::refuse_duplicate_tets() const {
  std::vector<std::array<int32_t, 4>> sorted(tets_);
  for (auto& t : sorted) std::sort(t.begin(), t.end());
  std::vector<uint32_t> order(tets_.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return sorted[a] != sorted[b] ? sorted[a] < sorted[b] : a < b; });
  for (size_t i = 1; i < order.size(); ++i)
    if (sorted[order[i]] == sorted[order[i - 1]])
      f_->fail_at(
          tet_position_[order[i]], "each tetrahedron once",
          fmt::format("element {} with the four nodes of element {} ({}); remove one of them",
                      tet_tag_[order[i]], tet_tag_[order[i - 1]], f_->where(tet_position_[order[i - 1]])));
}

// Two node tags at one point (within 1e-12 of the mesh's extent) that tets use: the tets around it are
// not connected there, an unmeant crack (an intended one: solid.fracture.initial_cracks).
void MshMeshBuilder::refuse_coincident_nodes() const {
  std::vector<uint8_t> used(nodes_.size(), 0);
  for (const auto& t : tets_)
    for (const int32_t v : t) used[static_cast<size_t>(v)] = 1;
  std::vector<uint32_t> order;
  Vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t n = 0; n < nodes_.size(); ++n)
    if (used[n]) {
      order.push_back(n);
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], nodes_[n][k]), hi[k] = std::max(hi[k], nodes_[n][k]);
    }
  if (order.empty()) return;
  const Vec3 extent = sub(hi, lo);
  const double tol = 1e-12 * std::sqrt(dot(extent, extent));
  // Sorted along a direction that no mesh's axes or lattice planes follow (sorted by x, every node of a
  // structured mesh would be compared with its whole plane of equal x): a partner within tol lies among the
  // following nodes whose projection is within tol (2 tol: the projections' round-off is far below tol).
  const double r2 = std::sqrt(2.0) - 1, r3 = std::sqrt(3.0) - 1, norm = std::sqrt(1 + r2 * r2 + r3 * r3);
  const Vec3 direction = {1 / norm, r2 / norm, r3 / norm};
  std::vector<double> along(nodes_.size());
  for (const uint32_t n : order) along[n] = dot(direction, sub(nodes_[n], lo));
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return along[a] != along[b] ? along[a] < along[b] : a < b; });
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && along[order[j]] - along[order[i]] <= 2 * tol; ++j) {
      const Vec3 d = sub(nodes_[order[j]], nodes_[order[i]]);
      if (dot(d, d) > tol * tol) continue;
      const uint32_t a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
      const Vec3& x = nodes_[a];
      f_->fail_at(node_position_[b], "each point once in the tets' nodes",
                  fmt::format("node {} at ({:.9g}, {:.9g}, {:.9g}), where node {} ({}) is; merge them "
                              "(Gmsh: Coherence) or, for a crack, use solid.fracture.initial_cracks",
                              node_tag_[b], x[0], x[1], x[2], node_tag_[a], f_->where(node_position_[a])));
    }
}

TetMesh MshMeshBuilder::finish(uint64_t content_hash, MshReadStats* stats) {
  refuse_duplicate_tets();
  refuse_coincident_nodes();
  TetMesh mesh;
  const auto& volume_entities = entity_physicals_[1];
  const auto& surface_entities = entity_physicals_[0];
  // Regions: physical volumes by tag, then "domain" for tets in none.
  const auto volumes = physical_groups(3, names_, volume_entities);
  for (const auto& [tag, name] : volumes) mesh.region_names.push_back(name);
  const auto volume_index = index_by_tag(volumes);
  std::unordered_map<int, int32_t> entity_region;  // volume entity -> region index
  for (const auto& [entity, physicals] : volume_entities)
    entity_region[entity] = volume_index.at(physicals.front());
  mesh.tet_region.reserve(tets_.size());
  int32_t domain = -1;
  for (const int entity : tet_entity_) {
    const auto it = entity_region.find(entity);
    if (it != entity_region.end()) {
      mesh.tet_region.push_back(it->second);
      continue;
    }
    if (domain < 0) {
      domain = mesh.region_index("domain");
      if (domain < 0) {
        domain = static_cast<int32_t>(mesh.region_names.size());
        mesh.region_names.push_back("domain");
      }
    }
    mesh.tet_region.push_back(domain);
  }
  // Surfaces: physical surfaces by tag; a triangle is listed once per physical surface of its entity.
  const auto surfaces = physical_groups(2, names_, surface_entities);
  for (const auto& [tag, name] : surfaces) mesh.surface_names.push_back(name);
  const auto surface_index = index_by_tag(surfaces);
  size_t unnamed = 0;
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const auto it = surface_entities.find(triangle_entity_[i]);
    if (it == surface_entities.end()) {
      ++unnamed;
      continue;
    }
    for (const int physical : it->second) {
      mesh.triangles.push_back(triangles_[i]);
      mesh.triangle_surface.push_back(surface_index.at(physical));
    }
  }
  // Keep only nodes that tets use, in file order.
  std::vector<int32_t> new_index(nodes_.size(), -1);
  for (const auto& tet : tets_)
    for (const int32_t v : tet) new_index[v] = 0;
  for (size_t i = 0; i < nodes_.size(); ++i) {
    if (new_index[i] < 0) continue;
    new_index[i] = static_cast<int32_t>(mesh.nodes.size());
    mesh.nodes.push_back(nodes_[i]);
  }
  mesh.tets = std::move(tets_);
  for (auto& tet : mesh.tets)
    for (int32_t& v : tet) v = new_index[v];
  for (auto& tri : mesh.triangles)
    for (int32_t& v : tri) {
      if (new_index[v] < 0)
        throw Error(f_->cursor().path() +
                    ": expected every surface triangle to use nodes of tetrahedra, found a "
                    "triangle on a node that no tetrahedron uses (is the volume meshed?)");
      v = new_index[v];
    }
  if (stats) {
    stats->content_fnv1a64 = content_hash;
    stats->nodes_in_file = nodes_.size();
    stats->unused_nodes_dropped = nodes_.size() - mesh.nodes.size();
    stats->tets = mesh.tets.size();
    stats->flipped_tets = flipped_;
    stats->triangles_without_surface = unnamed;
    stats->skipped_elements.assign(skipped_.begin(), skipped_.end());
  }
  return mesh;
}

}  // namespace rift
