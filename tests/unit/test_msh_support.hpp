#pragma once
// Shared by the MSH format tests: a small mesh described once (MshSpec) and written by the test itself in
// the four formats the reader takes (MSH 4.1 and 2.2, ASCII and binary), byte by byte, so that a test can
// change one thing (a count, a node tag, a byte) and know where the reader must stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift::test {

struct MshSpecEntity {
  std::vector<int> physicals, bounding;
};
struct MshSpecNode {
  int64_t tag;
  std::array<double, 3> x;
};
struct MshSpecNodeBlock {
  int dim, entity;
  std::vector<MshSpecNode> nodes;
};
struct MshSpecElementBlock {
  int dim, entity, type;
  std::vector<std::vector<int64_t>> elements;  // each: tag, node tags...
};

struct MshSpec {
  std::vector<std::tuple<int, int, std::string>> names;  // dim, physical tag, name
  std::map<int, MshSpecEntity> entities[4];              // per dimension: entity tag -> groups
  std::vector<MshSpecNodeBlock> node_blocks;
  std::vector<MshSpecElementBlock> element_blocks;
  // Lies a test may tell: the announced numbers of nodes and elements (-1: the true ones) and, in a binary
  // file, the endianness integer and the data size.
  int64_t announced_nodes = -1, announced_elements = -1;
  int one = 1, data_size = 8;
};

// Every part of two meshes is equal.
inline void expect_same_mesh(const TetMesh& a, const TetMesh& b) {
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.tet_region, b.tet_region);
  EXPECT_EQ(a.region_names, b.region_names);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_surface, b.triangle_surface);
  EXPECT_EQ(a.surface_names, b.surface_names);
}

// Three tets on sparse node tags 10..60 plus node 70 that only a point element uses. Tet 105 is positive,
// 106 and 107 negative. Volume entity 1 is in physicals 7 "rock" and 8, entity 2 in 9, entity 3 in none;
// surface entity 1 in physicals 3 "base" and 5, entity 2 in "base", entity 3 in none. A point (type 15), a
// line (type 1) and a 10-node tet (type 11) are skipped.
inline MshSpec cube_spec() {
  MshSpec s;
  s.names = {{3, 7, "rock"}, {2, 3, "base"}, {1, 11, "an edge"}};
  s.entities[0][1] = {};
  s.entities[1][1] = {{11}, {1, -1}};
  s.entities[2][1] = {{3, 5}, {1}};
  s.entities[2][2] = {{3}, {}};
  s.entities[2][3] = {};
  s.entities[3][1] = {{7, 8}, {1, 2}};
  s.entities[3][2] = {{9}, {}};
  s.entities[3][3] = {{}, {-3}};
  s.node_blocks = {{0, 1, {{70, {5, 5, 5}}}},
                   {3,
                    1,
                    {{10, {0, 0, 0}},
                     {20, {1, 0, 0}},
                     {30, {0, 0.1 + 0.2, 0}},
                     {40, {0, 0, 1}},
                     {50, {1, 1, 1.0 / 3.0}},
                     {60, {0, 0, -1e-3}}}}};
  s.element_blocks = {{0, 1, 15, {{100, 70}}},
                      {1, 1, 1, {{101, 10, 20}}},
                      {2, 1, 2, {{102, 10, 20, 40}}},
                      {2, 2, 2, {{103, 20, 50, 30}}},
                      {2, 3, 2, {{104, 10, 30, 40}}},
                      {3, 1, 4, {{105, 10, 20, 30, 40}}},
                      {3, 2, 4, {{106, 20, 40, 30, 50}}},
                      {3, 3, 4, {{107, 10, 20, 30, 60}}},
                      {3, 3, 11, {{108, 10, 20, 30, 40, 50, 60, 10, 20, 30, 40}}}};
  return s;
}

// `mesh` as an MshSpec: one node block (tags 1, 2, ...), one volume entity per region and one surface
// entity per surface name, each in the physical group of its tag (index + 1) with the mesh's name, elements
// in blocks of consecutive equal group.
inline MshSpec spec_of(const TetMesh& mesh) {
  MshSpec s;
  for (size_t r = 0; r < mesh.region_names.size(); ++r) {
    s.names.emplace_back(3, static_cast<int>(r + 1), mesh.region_names[r]);
    s.entities[3][static_cast<int>(r + 1)] = {{static_cast<int>(r + 1)}, {}};
  }
  for (size_t f = 0; f < mesh.surface_names.size(); ++f) {
    s.names.emplace_back(2, static_cast<int>(f + 1), mesh.surface_names[f]);
    s.entities[2][static_cast<int>(f + 1)] = {{static_cast<int>(f + 1)}, {}};
  }
  s.node_blocks.push_back({3, 1, {}});
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
    s.node_blocks[0].nodes.push_back({static_cast<int64_t>(n + 1), mesh.nodes[n]});
  int64_t tag = 1;
  auto add = [&](int dim, int group, int type, std::vector<int64_t> element) {
    if (s.element_blocks.empty() || s.element_blocks.back().dim != dim ||
        s.element_blocks.back().entity != group + 1)
      s.element_blocks.push_back({dim, group + 1, type, {}});
    element.insert(element.begin(), tag++);
    s.element_blocks.back().elements.push_back(std::move(element));
  };
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    add(3, mesh.tet_region[t], 4, {v[0] + 1, v[1] + 1, v[2] + 1, v[3] + 1});
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& v = mesh.triangles[t];
    add(2, mesh.triangle_surface[t], 2, {v[0] + 1, v[1] + 1, v[2] + 1});
  }
  return s;
}

// Values written as ASCII tokens or as little-endian binary (int: 4 bytes, size_t and double: 8).
class MshOut {
 public:
  explicit MshOut(bool binary) : binary_(binary) {}
  MshOut& i(int v) { return put(std::to_string(v), &v, 4); }
  MshOut& z(uint64_t v) { return put(std::to_string(v), &v, 8); }
  MshOut& d(double v) { return put(fmt_double(v), &v, 8); }
  // The end of a record: a newline in ASCII, nothing in binary.
  MshOut& nl() {
    if (!binary_) {
      if (!bytes.empty() && bytes.back() == ' ') bytes.pop_back();
      bytes += '\n';
    }
    return *this;
  }
  MshOut& text(const std::string& s) {
    bytes += s;
    return *this;
  }
  // The end of a section's binary data: Gmsh ends it with a newline before $End....
  MshOut& end(const std::string& marker) {
    if (binary_) bytes += '\n';
    return text(marker + "\n");
  }
  bool binary() const { return binary_; }
  std::string bytes;

 private:
  static std::string fmt_double(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
  }
  MshOut& put(const std::string& token, const void* value, size_t size) {
    if (binary_)
      bytes.append(static_cast<const char*>(value), size);  // the test machine is little-endian
    else
      bytes += token + ' ';
    return *this;
  }
  bool binary_;
};

inline void write_header(MshOut& o, const MshSpec& s, const char* version) {
  o.text(std::string("$MeshFormat\n") + version + (o.binary() ? " 1 " : " 0 ") + std::to_string(s.data_size) +
         "\n");
  if (o.binary()) {
    o.bytes.append(reinterpret_cast<const char*>(&s.one), 4);
    o.bytes += '\n';
  }
  o.text("$EndMeshFormat\n$PhysicalNames\n" + std::to_string(s.names.size()) + "\n");
  for (const auto& [dim, tag, name] : s.names)
    o.text(std::to_string(dim) + " " + std::to_string(tag) + " \"" + name + "\"\n");
  o.text("$EndPhysicalNames\n");
}

inline std::string write_msh41(const MshSpec& s, bool binary) {
  MshOut o(binary);
  write_header(o, s, "4.1");
  o.text("$Entities\n");
  for (int dim = 0; dim < 4; ++dim) o.z(s.entities[dim].size());
  o.nl();
  for (int dim = 0; dim < 4; ++dim)
    for (const auto& [tag, e] : s.entities[dim]) {
      o.i(tag);
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) o.d(0.0);
      o.z(e.physicals.size());
      for (const int p : e.physicals) o.i(p);
      if (dim > 0) {
        o.z(e.bounding.size());
        for (const int b : e.bounding) o.i(b);
      }
      o.nl();
    }
  o.end("$EndEntities").text("$Nodes\n");
  size_t nodes = 0;
  for (const auto& b : s.node_blocks) nodes += b.nodes.size();
  int64_t min_tag = INT64_MAX, max_tag = 0;
  for (const auto& b : s.node_blocks)
    for (const auto& n : b.nodes) min_tag = std::min(min_tag, n.tag), max_tag = std::max(max_tag, n.tag);
  o.z(s.node_blocks.size()).z(s.announced_nodes >= 0 ? s.announced_nodes : nodes).z(min_tag).z(max_tag).nl();
  for (const auto& b : s.node_blocks) {
    o.i(b.dim).i(b.entity).i(0).z(b.nodes.size()).nl();
    for (const auto& n : b.nodes) o.z(n.tag).nl();
    for (const auto& n : b.nodes) o.d(n.x[0]).d(n.x[1]).d(n.x[2]).nl();
  }
  o.end("$EndNodes").text("$Elements\n");
  size_t elements = 0;
  for (const auto& b : s.element_blocks) elements += b.elements.size();
  min_tag = INT64_MAX, max_tag = 0;
  for (const auto& b : s.element_blocks)
    for (const auto& e : b.elements) min_tag = std::min(min_tag, e[0]), max_tag = std::max(max_tag, e[0]);
  o.z(s.element_blocks.size())
      .z(s.announced_elements >= 0 ? s.announced_elements : elements)
      .z(min_tag)
      .z(max_tag)
      .nl();
  for (const auto& b : s.element_blocks) {
    o.i(b.dim).i(b.entity).i(b.type).z(b.elements.size()).nl();
    for (const auto& e : b.elements) {
      for (const int64_t v : e) o.z(static_cast<uint64_t>(v));
      o.nl();
    }
  }
  o.end("$EndElements");
  return o.bytes;
}

// MSH 2.2 as Gmsh writes it: an element once per physical group of its entity (tags: physical, entity;
// physical 0 when none), a copy numbered 1000 above the element; binary blocks of equal type.
inline std::string write_msh22(const MshSpec& s, bool binary) {
  MshOut o(binary);
  write_header(o, s, "2.2");
  size_t nodes = 0;
  for (const auto& b : s.node_blocks) nodes += b.nodes.size();
  o.text("$Nodes\n" + std::to_string(s.announced_nodes >= 0 ? s.announced_nodes : nodes) + "\n");
  for (const auto& b : s.node_blocks)
    for (const auto& n : b.nodes) o.i(static_cast<int>(n.tag)).d(n.x[0]).d(n.x[1]).d(n.x[2]).nl();
  struct Record {
    int type;
    std::vector<int> values;  // number, physical, entity, nodes...
  };
  std::vector<Record> records;
  for (const auto& b : s.element_blocks) {
    const auto it = s.entities[b.dim].find(b.entity);
    std::vector<int> physicals = it == s.entities[b.dim].end() ? std::vector<int>{} : it->second.physicals;
    if (physicals.empty()) physicals = {0};
    for (const auto& e : b.elements)
      for (size_t p = 0; p < physicals.size(); ++p) {
        Record r{b.type, {static_cast<int>(e[0] + 1000 * static_cast<int64_t>(p)), physicals[p], b.entity}};
        for (size_t k = 1; k < e.size(); ++k) r.values.push_back(static_cast<int>(e[k]));
        records.push_back(r);
      }
  }
  o.end("$EndNodes").text("$Elements\n");
  o.text(std::to_string(s.announced_elements >= 0 ? s.announced_elements : records.size()) + "\n");
  for (size_t i = 0; i < records.size();) {
    size_t j = i;
    while (j < records.size() && records[j].type == records[i].type) ++j;
    if (binary) o.i(records[i].type).i(static_cast<int>(j - i)).i(2);
    for (; i < j; ++i) {
      o.i(records[i].values[0]);
      if (!binary) o.i(records[i].type).i(2);
      for (size_t k = 1; k < records[i].values.size(); ++k) o.i(records[i].values[k]);
      o.nl();
    }
  }
  o.end("$EndElements");
  return o.bytes;
}

// The four formats, by name.
struct MshFormatCase {
  std::string name;
  std::string (*write)(const MshSpec&, bool);
  bool binary;
};
inline const std::vector<MshFormatCase>& msh_formats() {
  static const std::vector<MshFormatCase> formats = {{"4.1 ASCII", write_msh41, false},
                                                     {"4.1 binary", write_msh41, true},
                                                     {"2.2 ASCII", write_msh22, false},
                                                     {"2.2 binary", write_msh22, true}};
  return formats;
}

inline std::string write_bytes(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return path.string();
}

// The message of read_msh(path) through a window of `window` bytes, or "no error" when it reads.
inline std::string msh_error(const std::string& path, size_t window = msh_window_bytes) {
  return error_of([&] {
    read_msh(path, 1.0, nullptr, {msh_default_max_bytes, "mesh.max_file_bytes"}, window);
  });
}

// The byte offset of the first occurrence of `what` in `bytes` (a test's marker for where an error is).
inline size_t offset_of(const std::string& bytes, const std::string& what) {
  const size_t at = bytes.find(what);
  EXPECT_NE(at, std::string::npos) << what;
  return at;
}

}  // namespace rift::test
