// Gmsh MSH 4.1 ASCII reader. Layout reference: the "MSH file format" chapter of the Gmsh manual.
// One pass over the file, streamed through a window (memory holds the mesh, not the text); every record is
// parsed once, node tags are mapped through a
// dense array (or a hash map when tags are very sparse) and physical tags through hash maps, so the cost
// is O(file size) however many physical groups the file has.
#include "engine/mesh/msh_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

#include "engine/core/error.hpp"
#include "engine/core/vec3.hpp"
#include "engine/mesh/text_cursor.hpp"

namespace rift {
namespace {

constexpr int kTriangle = 2;  // Gmsh element type numbers
constexpr int kTet = 4;

const char* kConvertHint =
    "; convert it with `gmsh in.msh -save -format msh41 -o out.msh` "
    "(or in the Gmsh GUI: File > Export, format Gmsh MSH, Version 4 ASCII)";

// Gmsh node tag -> dense 0-based index. Dense array when the tags are reasonably compact (the usual
// case, O(1) without hashing), hash map for the rest.
class NodeTagMap {
 public:
  void reserve(int64_t max_tag, int64_t count) {
    if (max_tag >= 0 && max_tag <= 4 * count + 1024)
      dense_.assign(static_cast<size_t>(max_tag) + 1, -1);
    else
      sparse_.reserve(static_cast<size_t>(count));
  }
  bool insert(int64_t tag, int32_t index) {  // false when the tag is already present
    if (tag >= 0 && static_cast<size_t>(tag) < dense_.size()) {
      if (dense_[tag] >= 0) return false;
      dense_[tag] = index;
      return true;
    }
    return sparse_.emplace(tag, index).second;
  }
  int32_t find(int64_t tag) const {  // -1 when absent
    if (tag >= 0 && static_cast<size_t>(tag) < dense_.size()) return dense_[tag];
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? -1 : it->second;
  }

 private:
  std::vector<int32_t> dense_;
  std::unordered_map<int64_t, int32_t> sparse_;
};

class MshParser {
 public:
  MshParser(InputFileReader& file, const std::string& path, double scale, size_t window_bytes)
      : cur_(file, path, window_bytes), scale_(scale), max_records_(static_cast<int64_t>(file.size() / 2)) {}
  TetMesh parse(MshReadStats* stats);

 private:
  void read_format();
  void read_physical_names();
  void read_entities();
  void read_entity_list(int dim, int64_t count);
  void read_nodes();
  void read_elements();
  void read_element_block(int dim, int entity, int type, int64_t count);
  void read_tet(int entity);
  void skip_elements(int type, int64_t count);
  void expect_end(std::string_view end_marker);
  int64_t count(std::string_view what);
  TetMesh assemble(MshReadStats* stats);
  void refuse_duplicate_tets() const;
  void refuse_coincident_nodes() const;

  TextCursor cur_;
  double scale_;
  int64_t max_records_;  // each record holds a number and a separator: bounds counts that size allocations
  bool have_nodes_ = false, have_elements_ = false;
  std::map<std::pair<int, int>, std::string> physical_names_;      // (dim, physical tag) -> name
  std::unordered_map<int, std::vector<int>> entity_physicals_[4];  // per dim: entity tag -> physical tags
  std::vector<Vec3> nodes_;
  NodeTagMap node_index_;
  std::vector<std::array<int32_t, 4>> tets_;
  std::vector<int> tet_entity_;
  std::vector<int64_t> tet_tag_;  // the element tag and line of each tet, and each node's tag and line,
  std::vector<int> tet_line_;     // for the messages of the checks after reading
  std::vector<int64_t> node_tag_;
  std::vector<int> node_line_;
  std::vector<std::array<int32_t, 3>> triangles_;
  std::vector<int> triangle_entity_;
  std::map<int, size_t> skipped_;  // element type -> count
  size_t flipped_ = 0;
};

int64_t MshParser::count(std::string_view what) {
  const int64_t n = cur_.integer(what);
  if (n < 0) cur_.fail(std::string(what) + " >= 0", std::to_string(n));
  if (n > max_records_) cur_.fail(std::string(what) + " that fits in the file's size", std::to_string(n));
  return n;
}

void MshParser::expect_end(std::string_view end_marker) {
  const std::string_view t = cur_.token();
  if (t != end_marker) cur_.fail(std::string(end_marker), TextCursor::describe(t));
}

TetMesh MshParser::parse(MshReadStats* stats) {
  // A path in a scene can name any file: one that is not a mesh at all is refused without a word of it.
  const std::string_view first = cur_.token();
  if (first != "$MeshFormat")
    cur_.fail(
        "a Gmsh MSH file, which starts with $MeshFormat",
        first.empty() ? "an empty file" : "a file that does not (not a Gmsh mesh; its content is not shown)");
  read_format();
  for (std::string_view section = cur_.token(); !section.empty(); section = cur_.token()) {
    if (section.front() != '$') cur_.fail("a section name such as $Nodes", TextCursor::describe(section));
    if (section == "$MeshFormat")
      read_format();
    else if (section == "$PhysicalNames")
      read_physical_names();
    else if (section == "$Entities")
      read_entities();
    else if (section == "$Nodes")
      read_nodes();
    else if (section == "$Elements")
      read_elements();
    else if (section == "$PartitionedEntities")
      cur_.fail("an unpartitioned mesh", "$PartitionedEntities; save the mesh without partitions");
    else {
      // Copied: skipping moves the window under the token's view.
      const std::string name(section);
      const std::string end = "$End" + name.substr(1);
      const int line = cur_.line();
      if (!cur_.skip_past_line_starting(end)) cur_.fail_at(line, end + " closing " + name, "end of file");
    }
  }
  if (!have_nodes_) cur_.fail("a $Nodes section", "end of file");
  if (!have_elements_) cur_.fail("an $Elements section", "end of file");
  refuse_duplicate_tets();
  refuse_coincident_nodes();
  return assemble(stats);
}

void MshParser::read_format() {
  const std::string_view version = cur_.token();
  if (version != "4.1") cur_.fail("MSH format version 4.1", TextCursor::describe(version) + kConvertHint);
  const int64_t file_type = cur_.integer("file type");
  if (file_type != 0)
    cur_.fail("file type 0 (ASCII)", std::to_string(file_type) + " (binary)" + kConvertHint);
  const int64_t data_size = cur_.integer("data size");
  (void)data_size;  // only meaningful for binary files
  expect_end("$EndMeshFormat");
}

void MshParser::read_physical_names() {
  const int64_t n = count("number of physical names");
  for (int64_t i = 0; i < n; ++i) {
    const int64_t dim = cur_.integer("physical group dimension");
    if (dim < 0 || dim > 3) cur_.fail("a dimension 0..3", std::to_string(dim));
    const int64_t tag = cur_.integer("physical tag");
    physical_names_[{static_cast<int>(dim), static_cast<int>(tag)}] = cur_.quoted("physical name");
  }
  expect_end("$EndPhysicalNames");
}

void MshParser::read_entities() {
  int64_t n[4];
  n[0] = count("number of points");
  n[1] = count("number of curves");
  n[2] = count("number of surfaces");
  n[3] = count("number of volumes");
  for (int dim = 0; dim < 4; ++dim) read_entity_list(dim, n[dim]);
  expect_end("$EndEntities");
}

// Points: tag x y z nPhys phys...; curves, surfaces, volumes: tag bbox(6) nPhys phys... nBound bound...
void MshParser::read_entity_list(int dim, int64_t n) {
  for (int64_t i = 0; i < n; ++i) {
    const int tag = static_cast<int>(cur_.integer("entity tag"));
    for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) cur_.real("entity coordinate");
    std::vector<int> physicals(static_cast<size_t>(count("number of physical tags")));
    for (int& p : physicals) p = static_cast<int>(cur_.integer("physical tag"));
    if (!physicals.empty()) entity_physicals_[dim][tag] = std::move(physicals);
    if (dim > 0) {
      const int64_t bounding = count("number of bounding entities");
      for (int64_t k = 0; k < bounding; ++k) cur_.integer("bounding entity tag");
    }
  }
}

// numEntityBlocks numNodes minNodeTag maxNodeTag, then per block:
// entityDim entityTag parametric numNodesInBlock, the block's tags, then its coordinates.
void MshParser::read_nodes() {
  const int64_t blocks = count("number of node entity blocks");
  const int64_t total = count("number of nodes");
  const int header_line = cur_.line();
  cur_.integer("minimum node tag");
  node_index_.reserve(cur_.integer("maximum node tag"), total);
  nodes_.reserve(static_cast<size_t>(total));
  std::vector<int64_t> tags;
  for (int64_t b = 0; b < blocks; ++b) {
    const int64_t dim = cur_.integer("entity dimension");
    cur_.integer("entity tag");
    const int64_t parametric = cur_.integer("parametric flag (0 or 1)");
    const int64_t n = count("number of nodes in block");
    tags.resize(static_cast<size_t>(n));
    for (int64_t& t : tags) t = cur_.integer("node tag");
    const int extra = parametric ? static_cast<int>(dim) : 0;  // u, (v, (w)) after x y z
    for (const int64_t t : tags) {
      if (!node_index_.insert(t, static_cast<int32_t>(nodes_.size())))
        cur_.fail("node tags to be unique", "node tag " + std::to_string(t) + " a second time");
      Vec3 x;
      node_tag_.push_back(t);
      for (double& c : x) c = cur_.real("node coordinate") * scale_;
      node_line_.push_back(cur_.line());
      for (int k = 0; k < extra; ++k) cur_.real("parametric coordinate");
      nodes_.push_back(x);
    }
  }
  expect_end("$EndNodes");
  if (static_cast<int64_t>(nodes_.size()) != total)
    cur_.fail(std::to_string(total) + " nodes as announced on line " + std::to_string(header_line),
              std::to_string(nodes_.size()) + " nodes in the blocks");
  have_nodes_ = true;
}

// numEntityBlocks numElements minElementTag maxElementTag, then per block:
// entityDim entityTag elementType numElementsInBlock, then one element per line: tag nodeTags...
void MshParser::read_elements() {
  if (!have_nodes_) cur_.fail("$Nodes before $Elements", "$Elements");
  const int64_t blocks = count("number of element entity blocks");
  const int64_t total = count("number of elements");
  const int header_line = cur_.line();
  cur_.integer("minimum element tag");
  cur_.integer("maximum element tag");
  int64_t seen = 0;
  for (int64_t b = 0; b < blocks; ++b) {
    const int dim = static_cast<int>(cur_.integer("entity dimension"));
    const int entity = static_cast<int>(cur_.integer("entity tag"));
    const int type = static_cast<int>(cur_.integer("element type"));
    const int64_t n = count("number of elements in block");
    read_element_block(dim, entity, type, n);
    seen += n;
  }
  expect_end("$EndElements");
  if (seen != total)
    cur_.fail(std::to_string(total) + " elements as announced on line " + std::to_string(header_line),
              std::to_string(seen) + " elements in the blocks");
  have_elements_ = true;
}

void MshParser::read_element_block(int dim, int entity, int type, int64_t n) {
  if (type == kTet) {
    for (int64_t i = 0; i < n; ++i) read_tet(dim == 3 ? entity : -1);
  } else if (type == kTriangle) {
    for (int64_t i = 0; i < n; ++i) {
      const int64_t tag = cur_.integer("element tag");
      std::array<int32_t, 3> tri;
      for (int32_t& v : tri) {
        const int64_t node = cur_.integer("node tag");
        v = node_index_.find(node);
        if (v < 0)
          cur_.fail("a node tag defined in $Nodes",
                    std::to_string(node) + " in element " + std::to_string(tag));
      }
      triangles_.push_back(tri);
      triangle_entity_.push_back(dim == 2 ? entity : -1);
    }
  } else {
    skip_elements(type, n);
  }
}

void MshParser::read_tet(int entity) {
  const int64_t tag = cur_.integer("element tag");
  tet_tag_.push_back(tag);
  tet_line_.push_back(cur_.line());
  std::array<int32_t, 4> tet;
  for (int32_t& v : tet) {
    const int64_t node = cur_.integer("node tag");
    v = node_index_.find(node);
    if (v < 0)
      cur_.fail("a node tag defined in $Nodes", std::to_string(node) + " in element " + std::to_string(tag));
  }
  const Vec3 &x0 = nodes_[tet[0]], &x1 = nodes_[tet[1]], &x2 = nodes_[tet[2]], &x3 = nodes_[tet[3]];
  const Vec3 e1 = sub(x1, x0), e2 = sub(x2, x0), e3 = sub(x3, x0);
  const double six_v = dot(e1, cross(e2, e3));
  double h2 = std::max({dot(e1, e1), dot(e2, e2), dot(e3, e3)});
  h2 = std::max(
      {h2, dot(sub(x2, x1), sub(x2, x1)), dot(sub(x3, x1), sub(x3, x1)), dot(sub(x3, x2), sub(x3, x2))});
  // Relative threshold: |6V| / h^3 is 0.47 for a regular tet; 1e-14 is round-off of a flat one.
  if (!(std::abs(six_v) >= 1e-14 * h2 * std::sqrt(h2)))
    cur_.fail("a tetrahedron with non-zero volume",
              fmt::format("element {} with 6V = {:.3g} for longest edge {:.6g}", tag, six_v, std::sqrt(h2)));
  if (six_v < 0) {
    std::swap(tet[1], tet[2]);
    ++flipped_;
  }
  tets_.push_back(tet);
  tet_entity_.push_back(entity);
}

// A tet listed twice (the same four nodes in any order) would count its volume and mass twice.
void MshParser::refuse_duplicate_tets() const {
  std::vector<std::array<int32_t, 4>> sorted(tets_);
  for (auto& t : sorted) std::sort(t.begin(), t.end());
  std::vector<uint32_t> order(tets_.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return sorted[a] != sorted[b] ? sorted[a] < sorted[b] : a < b; });
  for (size_t i = 1; i < order.size(); ++i)
    if (sorted[order[i]] == sorted[order[i - 1]])
      cur_.fail_at(tet_line_[order[i]], "each tetrahedron once",
                   fmt::format("element {} with the four nodes of element {} (line {}); remove one of them",
                               tet_tag_[order[i]], tet_tag_[order[i - 1]], tet_line_[order[i - 1]]));
}

// Two node tags at one point (within 1e-12 of the mesh's extent) that tets use: the tets around it are
// not connected there, an unmeant crack (an intended one: solid.fracture.initial_cracks).
void MshParser::refuse_coincident_nodes() const {
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
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return nodes_[a] != nodes_[b] ? nodes_[a] < nodes_[b] : a < b; });
  // Sorted by x first: a partner within tol lies among the following nodes whose x is within tol.
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && nodes_[order[j]][0] - nodes_[order[i]][0] <= tol; ++j) {
      const Vec3 d = sub(nodes_[order[j]], nodes_[order[i]]);
      if (dot(d, d) > tol * tol) continue;
      const uint32_t a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
      const Vec3& x = nodes_[a];
      cur_.fail_at(node_line_[b], "each point once in the tets' nodes",
                   fmt::format("node {} at ({:.9g}, {:.9g}, {:.9g}), where node {} (line {}) is; merge them "
                               "(Gmsh: Coherence) or, for a crack, use solid.fracture.initial_cracks",
                               node_tag_[b], x[0], x[1], x[2], node_tag_[a], node_line_[a]));
    }
}

// Element types we do not use are skipped line by line: Gmsh writes one element per line, so this needs
// no table of node counts per type.
void MshParser::skip_elements(int type, int64_t n) {
  cur_.skip_rest_of_line();
  for (int64_t i = 0; i < n; ++i) {
    const std::string_view next = cur_.peek();
    if (next.empty() || next.front() == '$')
      cur_.fail(std::to_string(n) + " elements of type " + std::to_string(type) + " in this block",
                TextCursor::describe(next) + " after " + std::to_string(i));
    cur_.token();
    cur_.skip_rest_of_line();
  }
  skipped_[type] += static_cast<size_t>(n);
}

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

TetMesh MshParser::assemble(MshReadStats* stats) {
  TetMesh mesh;
  // Regions: physical volumes by tag, then "domain" for tets in none.
  const auto volumes = physical_groups(3, physical_names_, entity_physicals_[3]);
  for (const auto& [tag, name] : volumes) mesh.region_names.push_back(name);
  const auto volume_index = index_by_tag(volumes);
  std::unordered_map<int, int32_t> entity_region;  // volume entity -> region index
  for (const auto& [entity, physicals] : entity_physicals_[3])
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
  const auto surfaces = physical_groups(2, physical_names_, entity_physicals_[2]);
  for (const auto& [tag, name] : surfaces) mesh.surface_names.push_back(name);
  const auto surface_index = index_by_tag(surfaces);
  size_t unnamed = 0;
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const auto it = entity_physicals_[2].find(triangle_entity_[i]);
    if (triangle_entity_[i] < 0 || it == entity_physicals_[2].end()) {
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
        throw Error(cur_.path() +
                    ": expected every surface triangle to use nodes of tetrahedra, found a "
                    "triangle on a node that no tetrahedron uses (is the volume meshed?)");
      v = new_index[v];
    }
  if (stats) {
    stats->content_fnv1a64 = cur_.content_hash();  // the whole file: parsing ends at its end
    stats->nodes_in_file = nodes_.size();
    stats->unused_nodes_dropped = nodes_.size() - mesh.nodes.size();
    stats->tets = mesh.tets.size();
    stats->flipped_tets = flipped_;
    stats->triangles_without_surface = unnamed;
    stats->skipped_elements.assign(skipped_.begin(), skipped_.end());
  }
  return mesh;
}

}  // namespace

TetMesh read_msh(const std::string& path, double scale, MshReadStats* stats, const InputFileLimit& limit,
                 size_t window_bytes) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw Error(path + ": expected a positive mesh scale, found " + std::to_string(scale));
  InputFileReader file(path, limit, "mesh file");
  MshReadStats local;
  TetMesh mesh = MshParser(file, path, scale, window_bytes).parse(&local);
  if (stats) *stats = local;
  if (mesh.tets.empty()) {
    std::string found = "none";
    if (!local.skipped_elements.empty()) {
      found = "only other element types:";
      for (const auto& [type, n] : local.skipped_elements)
        found += " " + std::to_string(n) + " of type " + std::to_string(type);
      found += " (re-mesh with first-order tets: Mesh.ElementOrder = 1)";
    }
    throw Error(path + ": expected 4-node tetrahedra (element type 4), found " + found);
  }
  return mesh;
}

}  // namespace rift
