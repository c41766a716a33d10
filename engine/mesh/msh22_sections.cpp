// MSH 2.2 $Nodes and $Elements, ASCII and binary. Both start with their count as a text line; binary data
// follows on the next line. Nodes: number x y z (binary: int, 3 doubles). Elements in ASCII: number type
// numTags tags... nodes...; in binary, blocks of one type: a header (type, count, numTags) and then count
// records (number, tags..., nodes...), all int. The first tag is the physical group, the second the
// elementary (geometric) entity; physical tag 0 means none.
// MSH 2.2 keeps no entities: an element's physical group stands in for its entity (an entity of that one
// group), which gives the names of msh_reader.hpp. Gmsh writes an element of an entity in several physical
// groups once per group, in a row: a tet repeated so (same nodes and elementary entity, another physical
// group) is kept once, in its first group, as MSH 4.1's entity in several physical volumes; a triangle is
// listed once per group, as in 4.1.
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/mesh/msh_element_types.hpp"
#include "engine/mesh/msh_sections.hpp"

namespace rift {
namespace {

class Msh22Elements {
 public:
  explicit Msh22Elements(MshMeshBuilder& mesh) : mesh_(&mesh) {}

  // One tet or triangle record: its number, tags and node numbers; `at` locates it for messages.
  void add(int type, int64_t number, const int* tags, int64_t n_tags, const int* nodes, uint64_t at) {
    const int physical = n_tags > 0 ? tags[0] : 0;
    const int elementary = n_tags > 1 ? tags[1] : 0;
    const int dim = type == kMshTet ? 3 : 2;
    const int entity = physical == 0 ? kMshNoEntity : physical;
    if (physical != 0 && !mesh_->has_entity_groups(dim, physical))
      mesh_->set_entity_groups(dim, physical, {physical});
    if (type == kMshTriangle) {
      const int64_t tri[3] = {nodes[0], nodes[1], nodes[2]};
      mesh_->add_triangle(number, tri, entity, at);
      return;
    }
    const int64_t tet[4] = {nodes[0], nodes[1], nodes[2], nodes[3]};
    const bool copy = have_last_ && std::equal(tet, tet + 4, last_) && elementary == last_elementary_ &&
                      physical != last_physical_;
    std::copy(tet, tet + 4, last_);
    have_last_ = true;
    last_elementary_ = elementary;
    last_physical_ = physical;
    if (!copy) mesh_->add_tet(number, tet, entity, at);
  }

 private:
  MshMeshBuilder* mesh_;
  bool have_last_ = false;
  int64_t last_[4] = {};
  int last_elementary_ = 0, last_physical_ = 0;
};

void read_text_elements(MshFields& f, MshMeshBuilder& mesh, int64_t total) {
  Msh22Elements elements(mesh);
  std::vector<int> values;
  for (int64_t i = 0; i < total; ++i) {
    const int number = f.int32("element number");
    const uint64_t at = f.position();
    const int type = f.int32("element type");
    if (type != kMshTet && type != kMshTriangle) {  // one element per line: skipped without a table
      f.cursor().skip_rest_of_line();
      mesh.skip(type, 1);
      continue;
    }
    const int64_t n_tags = f.count(f.int32("number of tags"), "number of tags", 4);
    const int nodes = msh_nodes_per_element(type);
    values.resize(static_cast<size_t>(n_tags + nodes));
    f.int32s(values.data(), static_cast<size_t>(n_tags), "element tag");
    f.int32s(values.data() + n_tags, static_cast<size_t>(nodes), "node number");
    elements.add(type, number, values.data(), n_tags, values.data() + n_tags, at);
  }
}

void read_binary_elements(MshFields& f, MshMeshBuilder& mesh, int64_t total, int count_line) {
  Msh22Elements elements(mesh);
  std::vector<int> record;
  for (int64_t seen = 0; seen < total;) {
    int header[3];
    f.int32s(header, 3, "an element block header (type, count, number of tags)");
    const int type = header[0];
    const int64_t n = header[1];
    if (n < 0 || n > total - seen)
      f.fail(fmt::format("a block of at most {} elements ({} as announced on line {}, {} read)", total - seen,
                         total, count_line, seen),
             "a block of " + std::to_string(n));
    const int64_t n_tags = f.count(header[2], "number of tags", 4);
    const int nodes = msh_nodes_per_element(type);
    if (nodes == 0)
      f.fail("an element type of known node count (binary records of another type cannot be skipped)",
             "element type " + std::to_string(type));
    const size_t length = static_cast<size_t>(1 + n_tags + nodes);
    if (type == kMshTet || type == kMshTriangle) {
      record.resize(length);
      for (int64_t i = 0; i < n; ++i) {
        f.int32s(record.data(), length, "an element record (number, tags, node numbers)");
        elements.add(type, record[0], record.data() + 1, n_tags, record.data() + 1 + n_tags, f.position());
      }
    } else {
      f.skip_bytes(static_cast<uint64_t>(n) * length * 4,
                   std::to_string(n) + " elements of type " + std::to_string(type) + " to skip");
      mesh.skip(type, static_cast<size_t>(n));
    }
    seen += n;
  }
}

}  // namespace

void read_msh22_nodes(MshFields& f, MshMeshBuilder& mesh) {
  const int64_t n = f.count(f.text_integer("number of nodes"), "number of nodes", 28);  // int, 3 doubles
  mesh.reserve_nodes(n, n);  // Gmsh numbers the nodes 1..n: a dense map
  f.begin_data();
  for (int64_t i = 0; i < n; ++i) {
    const int tag = f.int32("node number");
    double x[3];
    f.reals(x, 3, "node coordinate");
    mesh.add_node(tag, {x[0], x[1], x[2]}, f.position());
  }
  f.expect_end("$EndNodes");
}

void read_msh22_elements(MshFields& f, MshMeshBuilder& mesh) {
  const int64_t total = f.count(f.text_integer("number of elements"), "number of elements", 8);
  const int count_line = f.cursor().line();
  f.begin_data();
  if (f.binary())
    read_binary_elements(f, mesh, total, count_line);
  else
    read_text_elements(f, mesh, total);
  f.expect_end("$EndElements");
}

}  // namespace rift
