#pragma once
// Helpers for the mesh conversion tests: a solid topology from a TetMesh (every tet in the fracture
// zone unless told otherwise), and an independent check of a surface mesh: closed, oriented, its
// connected components with their Euler characteristic and enclosed volume.
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <numeric>
#include <vector>

#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/mesh_conversion.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift::test {

// Owns the discontinuous mesh the conversion's spans point into.
struct ConversionCase {
  TetMesh mesh;
  DiscontinuousMesh dm;
  std::vector<std::array<int32_t, 3>> notch;  // input vertex ids
  std::vector<double> x, v, mass;             // per solid node

  SolidTopology topology() const {
    SolidTopology t;
    t.input_vertex_count = mesh.nodes.size();
    t.node_vertex = dm.node_vertex;
    t.tet_nodes = {dm.tets.empty() ? nullptr : &dm.tets[0][0], 4 * dm.tets.size()};
    t.joint_nodes = {dm.joints.empty() ? nullptr : &dm.joints[0][0], 6 * dm.joints.size()};
    t.joint_tets = {dm.joint_tets.empty() ? nullptr : &dm.joint_tets[0][0], 2 * dm.joint_tets.size()};
    t.notch_triangles = notch;
    return t;
  }
  size_t joints() const { return dm.joints.size(); }
  // Centroid of joint j's face (reference configuration).
  std::array<double, 3> joint_centroid(size_t j) const {
    std::array<double, 3> c{0, 0, 0};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) c[k] += dm.nodes[dm.joints[j][i]][k] / 3.0;
    return c;
  }
};

inline ConversionCase make_case(TetMesh mesh, const std::function<bool(size_t)>& in_zone = {}) {
  ConversionCase c;
  c.mesh = std::move(mesh);
  c.dm = make_discontinuous(
      c.mesh, in_zone ? in_zone : [](size_t) { return true; });
  for (const auto& p : c.dm.nodes) c.x.insert(c.x.end(), p.begin(), p.end());
  c.v.assign(c.x.size(), 0.0);
  c.mass.assign(c.dm.nodes.size(), 1.0);
  return c;
}

struct SurfaceComponent {
  size_t vertices = 0, edges = 0, triangles = 0;
  double volume = 0.0;   // divergence theorem: sum of x0 . (x1 x x2) / 6 over its triangles
  bool manifold = true;  // every edge in exactly two triangles and one fan of triangles round every vertex
  long euler() const { return long(vertices) - long(edges) + long(triangles); }
};

struct SurfaceReport {
  bool closed_and_oriented = true;  // every directed edge a->b is matched by as many b->a
  size_t nonmanifold_edges = 0;     // edges in more than two triangles
  size_t pinched_vertices = 0;      // vertices (on manifold edges) with two or more fans of triangles
  std::vector<SurfaceComponent> components;  // by lowest vertex id
  double volume() const {
    double s = 0.0;
    for (const auto& c : components) s += c.volume;
    return s;
  }
};

inline int32_t root_of(std::vector<int32_t>& p, int32_t i) {
  while (p[i] != i) i = p[i] = p[p[i]];
  return i;
}

// Components are sets of triangles connected through shared vertices.
inline SurfaceReport analyse_surface(std::span<const int32_t> tri, std::span<const double> x,
                                     size_t vertex_count) {
  SurfaceReport r;
  const size_t nt = tri.size() / 3;
  std::vector<int32_t> parent(vertex_count);
  std::iota(parent.begin(), parent.end(), 0);
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (size_t t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i) {
      const int32_t a = tri[3 * t + i], b = tri[3 * t + (i + 1) % 3];
      ++directed[{a, b}];
      const int32_t ra = root_of(parent, a), rb = root_of(parent, b);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  std::map<int32_t, size_t> index;
  for (size_t t = 0; t < nt; ++t) index.try_emplace(root_of(parent, tri[3 * t]), 0);
  size_t k = 0;
  for (auto& [root, i] : index) i = k++;
  r.components.resize(index.size());
  std::vector<std::vector<int32_t>> verts(index.size());
  for (size_t t = 0; t < nt; ++t) {
    auto& c = r.components[index[root_of(parent, tri[3 * t])]];
    ++c.triangles;
    const double* p0 = &x[3 * tri[3 * t]];
    const double* p1 = &x[3 * tri[3 * t + 1]];
    const double* p2 = &x[3 * tri[3 * t + 2]];
    c.volume += (p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0]) +
                 p0[2] * (p1[0] * p2[1] - p1[1] * p2[0])) /
                6.0;
    for (int i = 0; i < 3; ++i) verts[index[root_of(parent, tri[3 * t])]].push_back(tri[3 * t + i]);
  }
  for (size_t i = 0; i < verts.size(); ++i) {
    std::sort(verts[i].begin(), verts[i].end());
    r.components[i].vertices = std::unique(verts[i].begin(), verts[i].end()) - verts[i].begin();
  }
  std::map<std::pair<int32_t, int32_t>, int> undirected;
  for (const auto& [e, n] : directed) {
    const auto back = directed.find({e.second, e.first});
    if (n != (back == directed.end() ? 0 : back->second)) r.closed_and_oriented = false;
    undirected[{std::min(e.first, e.second), std::max(e.first, e.second)}] += n;
  }
  for (const auto& [e, n] : undirected) {
    auto& c = r.components[index[root_of(parent, e.first)]];
    ++c.edges;
    if (n != 2) {
      c.manifold = false;
      ++r.nonmanifold_edges;
    }
  }
  // Fans: the triangles (a, b, c) round vertex a give link edges b -> c; on manifold edges these form
  // closed cycles, one per fan. More than one cycle: the surface touches itself at a.
  std::map<int32_t, std::map<int32_t, int32_t>> link;
  for (size_t t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i) link[tri[3 * t + i]][tri[3 * t + (i + 1) % 3]] = tri[3 * t + (i + 2) % 3];
  for (auto& [a, next] : link) {
    auto& c = r.components[index[root_of(parent, a)]];
    if (!c.manifold) continue;
    size_t cycles = 0;
    std::map<int32_t, bool> seen;
    for (const auto& [b, _] : next) {
      if (seen[b]) continue;
      ++cycles;
      for (int32_t e = b; !seen[e]; e = next.count(e) ? next[e] : b) seen[e] = true;
    }
    if (cycles > 1) {
      c.manifold = false;
      ++r.pinched_vertices;
    }
  }
  return r;
}

inline SurfaceReport analyse_surface(MeshConversion& conv, const ConversionCase& c) {
  conv.update_kinematics(c.x, c.v, c.mass);
  return analyse_surface(conv.triangle_vertices(), conv.vertex_x(), conv.vertex_count());
}

// Pieces of solid counted the slow, independent way: tets tied through intact joints, plus tets that
// share a node outside the fracture zone.
inline size_t tet_graph_components(const ConversionCase& c, const std::vector<uint8_t>& intact) {
  const size_t nt = c.dm.tets.size();
  std::vector<int32_t> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  auto unite = [&](int32_t a, int32_t b) {
    a = root_of(parent, a), b = root_of(parent, b);
    parent[std::max(a, b)] = std::min(a, b);
  };
  for (size_t j = 0; j < c.dm.joints.size(); ++j)
    if (intact[j]) unite(c.dm.joint_tets[j][0], c.dm.joint_tets[j][1]);
  std::vector<int32_t> first_tet(c.dm.nodes.size(), -1);
  for (size_t e = 0; e < nt; ++e)
    for (int32_t n : c.dm.tets[e]) {
      if (first_tet[n] >= 0) unite(first_tet[n], static_cast<int32_t>(e));
      first_tet[n] = static_cast<int32_t>(e);
    }
  size_t count = 0;
  for (size_t e = 0; e < nt; ++e) count += root_of(parent, static_cast<int32_t>(e)) == int32_t(e);
  return count;
}

// The grouping of node copies into vertices, independent of vertex numbering: each node is named by
// the lowest node of its vertex.
inline std::vector<int32_t> canonical_partition(const MeshConversion& conv) {
  const auto nv = conv.node_vertex();
  std::vector<int32_t> lowest(conv.vertex_count(), INT32_MAX), out(nv.size());
  for (size_t n = 0; n < nv.size(); ++n) lowest[nv[n]] = std::min<int32_t>(lowest[nv[n]], int32_t(n));
  for (size_t n = 0; n < nv.size(); ++n) out[n] = lowest[nv[n]];
  return out;
}

}  // namespace rift::test
