#pragma once
// The mesh an MSH reader builds while it parses, shared by the section readers of MSH 4.1 and 2.2, ASCII
// and binary: nodes by Gmsh tag, tets (checked and oriented as they come), triangles, the physical groups
// of the entities the elements are in, and the element types skipped. After parsing: the checks that need
// the whole mesh (duplicate tets, coincident nodes) and the assembly into a TetMesh with region and surface
// names by the rules of msh_reader.hpp. Every node and tet keeps its Gmsh tag and its place in the file
// (a line, or a byte offset in binary data) for the messages of those checks.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "engine/core/vec3.hpp"
#include "engine/mesh/msh_fields.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// The entity of an element that is in no entity of its dimension (a tet in a surface's block).
inline constexpr int kMshNoEntity = std::numeric_limits<int>::min();

// Gmsh node tag -> dense 0-based index. Dense array when the tags are reasonably compact (the usual
// case, O(1) without hashing), hash map for the rest.
class MshNodeTags {
 public:
  void reserve(int64_t max_tag, int64_t count);
  bool insert(int64_t tag, int32_t index);  // false when the tag is already present
  int32_t find(int64_t tag) const {         // -1 when absent
    if (tag >= 0 && static_cast<size_t>(tag) < dense_.size()) return dense_[tag];
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? -1 : it->second;
  }

 private:
  std::vector<int32_t> dense_;
  std::unordered_map<int64_t, int32_t> sparse_;
};

class MshMeshBuilder {
 public:
  // Messages go through `fields`; coordinates are multiplied by `scale` as they come.
  MshMeshBuilder(MshFields& fields, double scale) : f_(&fields), scale_(scale) {}

  // Groups: a name per (dimension, physical tag); the physical tags of an entity of dimension 2 or 3.
  void name_group(int dim, int tag, std::string name) { names_[{dim, tag}] = std::move(name); }
  void set_entity_groups(int dim, int entity, std::vector<int> physicals);
  bool has_entity_groups(int dim, int entity) const;

  // Nodes: `x` as in the file; `position` is f.position() of its record. A repeated tag is an error.
  void reserve_nodes(int64_t max_tag, int64_t count);
  void add_node(int64_t tag, const Vec3& x, uint64_t position);
  size_t node_count() const { return nodes_.size(); }

  // Elements by node tags; an undefined node tag, and a tet of no volume, are errors at `position`.
  void add_tet(int64_t tag, const int64_t (&node_tags)[4], int entity, uint64_t position);
  void add_triangle(int64_t tag, const int64_t (&node_tags)[3], int entity, uint64_t position);
  void skip(int type, size_t count) { skipped_[type] += count; }

  bool have_nodes = false, have_elements = false;  // sections read

  // The checks and the assembly; `content_hash` goes to the stats.
  TetMesh finish(uint64_t content_hash, MshReadStats* stats);

 private:
  int32_t node_index(int64_t node_tag, int64_t element_tag, uint64_t position) const;
  void refuse_duplicate_tets() const;
  void refuse_coincident_nodes() const;

  MshFields* f_;
  double scale_;
  std::map<std::pair<int, int>, std::string> names_;               // (dim, physical tag) -> name
  std::unordered_map<int, std::vector<int>> entity_physicals_[2];  // dims 2, 3: entity -> physical tags
  std::vector<Vec3> nodes_;
  MshNodeTags node_index_;
  std::vector<int64_t> node_tag_;
  std::vector<uint64_t> node_position_;
  std::vector<std::array<int32_t, 4>> tets_;
  std::vector<int> tet_entity_;
  std::vector<int64_t> tet_tag_;
  std::vector<uint64_t> tet_position_;
  std::vector<std::array<int32_t, 3>> triangles_;
  std::vector<int> triangle_entity_;
  std::map<int, size_t> skipped_;  // element type -> count
  size_t flipped_ = 0;
};

}  // namespace rift
