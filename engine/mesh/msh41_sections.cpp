// MSH 4.1 $Entities, $Nodes and $Elements, ASCII and binary: the same sequence of values, as text or as
// binary (int for dimensions, entity tags, element types and physical tags; size_t for counts and node
// and element tags; double for coordinates). A binary section's data starts on the line after its name.
#include <string>
#include <vector>

#include "engine/mesh/msh_element_types.hpp"
#include "engine/mesh/msh_sections.hpp"

namespace rift {
namespace {

// Bytes of the smallest binary record of each kind, for the count checks: an entity block header
// (3 ints, a size_t); a node (size_t tag, 3 doubles); an element (size_t tag, a size_t node).
constexpr uint64_t kBlockHeaderBytes = 20, kNodeBytes = 32, kElementBytes = 16;

int checked_dimension(MshFields& f, std::string_view what) {
  const int dim = f.int32(what);
  if (dim < 0 || dim > 3) f.fail("an entity dimension 0..3", std::to_string(dim));
  return dim;
}

// ASCII element records of a type the reader does not use are skipped line by line: Gmsh writes one
// element per line, so this needs no table of node counts per type.
void skip_text_elements(TextCursor& cur, int type, int64_t n) {
  cur.skip_rest_of_line();
  for (int64_t i = 0; i < n; ++i) {
    const std::string_view next = cur.peek();
    if (next.empty() || next.front() == '$')
      cur.fail(std::to_string(n) + " elements of type " + std::to_string(type) + " in this block",
               TextCursor::describe(next) + " after " + std::to_string(i));
    cur.token();
    cur.skip_rest_of_line();
  }
}

// `type_at`: where the block's element type is, for the message that refuses it.
void read_element_block(MshFields& f, MshMeshBuilder& mesh, int dim, int entity, int type, uint64_t type_at,
                        int64_t n) {
  if (type == kMshTet) {
    for (int64_t i = 0; i < n; ++i) {
      const int64_t tag = f.size("element tag");
      const uint64_t at = f.position();
      int64_t nodes[4];
      f.sizes(nodes, 4, "node tag");
      mesh.add_tet(tag, nodes, dim == 3 ? entity : kMshNoEntity, at);
    }
  } else if (type == kMshTriangle) {
    for (int64_t i = 0; i < n; ++i) {
      const int64_t tag = f.size("element tag");
      const uint64_t at = f.position();
      int64_t nodes[3];
      f.sizes(nodes, 3, "node tag");
      mesh.add_triangle(tag, nodes, dim == 2 ? entity : kMshNoEntity, at);
    }
  } else if (!f.binary()) {
    skip_text_elements(f.cursor(), type, n);
    mesh.skip(type, static_cast<size_t>(n));
  } else {
    const int nodes = msh_nodes_per_element(type);
    if (nodes == 0)
      f.fail_at(type_at,
                "an element type of known node count (binary records of another type cannot be skipped)",
                "element type " + std::to_string(type));
    f.skip_bytes(static_cast<uint64_t>(n) * 8 * (1 + static_cast<uint64_t>(nodes)),
                 std::to_string(n) + " elements of type " + std::to_string(type) + " to skip");
    mesh.skip(type, static_cast<size_t>(n));
  }
}

}  // namespace

// numPoints numCurves numSurfaces numVolumes, then points: tag x y z numPhysicals physicals...; curves,
// surfaces, volumes: tag minX minY minZ maxX maxY maxZ numPhysicals physicals... numBounding bounding...
void read_msh41_entities(MshFields& f, MshMeshBuilder& mesh) {
  f.begin_data();
  static constexpr const char* kCounts[4] = {"number of points", "number of curves", "number of surfaces",
                                             "number of volumes"};
  int64_t n[4];
  for (int dim = 0; dim < 4; ++dim) n[dim] = f.count(f.size(kCounts[dim]), kCounts[dim], dim == 0 ? 36 : 68);
  std::vector<int> bounding;
  for (int dim = 0; dim < 4; ++dim)
    for (int64_t i = 0; i < n[dim]; ++i) {
      const int tag = f.int32("entity tag");
      double box[6];
      f.reals(box, dim == 0 ? 3 : 6, "entity coordinate");
      std::vector<int> physicals(
          static_cast<size_t>(f.count(f.size("number of physical tags"), "number of physical tags", 4)));
      f.int32s(physicals.data(), physicals.size(), "physical tag");
      if (dim > 0) {
        bounding.resize(static_cast<size_t>(
            f.count(f.size("number of bounding entities"), "number of bounding entities", 4)));
        f.int32s(bounding.data(), bounding.size(), "bounding entity tag");
      }
      mesh.set_entity_groups(dim, tag, std::move(physicals));
    }
  f.expect_end("$EndEntities");
}

// numEntityBlocks numNodes minNodeTag maxNodeTag, then per block:
// entityDim entityTag parametric numNodesInBlock, the block's tags, then its coordinates.
void read_msh41_nodes(MshFields& f, MshMeshBuilder& mesh) {
  f.begin_data();
  const int64_t blocks =
      f.count(f.size("number of node entity blocks"), "number of node entity blocks", kBlockHeaderBytes);
  const int64_t total = f.count(f.size("number of nodes"), "number of nodes", kNodeBytes);
  const uint64_t header = f.position();
  f.size("minimum node tag");
  mesh.reserve_nodes(f.size("maximum node tag"), total);
  std::vector<int64_t> tags;
  for (int64_t b = 0; b < blocks; ++b) {
    const int dim = checked_dimension(f, "entity dimension");
    f.int32("entity tag");
    const int parametric = f.int32("parametric flag (0 or 1)");
    const int64_t n = f.count(f.size("number of nodes in block"), "number of nodes in block", kNodeBytes);
    tags.resize(static_cast<size_t>(n));
    f.sizes(tags.data(), tags.size(), "node tag");
    const int extra = parametric ? dim : 0;  // u, (v, (w)) after x y z
    for (const int64_t tag : tags) {
      double x[6];
      f.reals(x, 3, "node coordinate");
      const uint64_t at = f.position();
      f.reals(x + 3, static_cast<size_t>(extra), "parametric coordinate");
      mesh.add_node(tag, {x[0], x[1], x[2]}, at);
    }
  }
  f.expect_end("$EndNodes");
  if (static_cast<int64_t>(mesh.node_count()) != total)
    f.fail(std::to_string(total) + " nodes as announced " + f.at(header),
           std::to_string(mesh.node_count()) + " nodes in the blocks");
}

// numEntityBlocks numElements minElementTag maxElementTag, then per block:
// entityDim entityTag elementType numElementsInBlock, then per element: tag nodeTags...
void read_msh41_elements(MshFields& f, MshMeshBuilder& mesh) {
  f.begin_data();
  const int64_t blocks = f.count(f.size("number of element entity blocks"), "number of element entity blocks",
                                 kBlockHeaderBytes);
  const int64_t total = f.count(f.size("number of elements"), "number of elements", kElementBytes);
  const uint64_t header = f.position();
  f.size("minimum element tag");
  f.size("maximum element tag");
  int64_t seen = 0;
  for (int64_t b = 0; b < blocks; ++b) {
    const int dim = checked_dimension(f, "entity dimension");
    const int entity = f.int32("entity tag");
    const int type = f.int32("element type");
    const uint64_t type_at = f.position();
    const int64_t n =
        f.count(f.size("number of elements in block"), "number of elements in block", kElementBytes);
    read_element_block(f, mesh, dim, entity, type, type_at, n);
    seen += n;
  }
  f.expect_end("$EndElements");
  if (seen != total)
    f.fail(std::to_string(total) + " elements as announced " + f.at(header),
           std::to_string(seen) + " elements in the blocks");
}

}  // namespace rift
