#include "engine/mesh/mesh_conversion.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "engine/core/error.hpp"
#include "engine/mesh/tet_faces.hpp"
#include "engine/schedule/parallel.hpp"

namespace rift {

namespace {

// The local face of a tet that holds three of its corners (the corner left out), or -1.
int face_holding(const int32_t* tet, const int32_t* corners) {
  for (int f = 0; f < 4; ++f)
    if (tet[f] != corners[0] && tet[f] != corners[1] && tet[f] != corners[2]) return f;
  return -1;
}

int32_t find_root(std::vector<int32_t>& parent, int32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Union by smaller index, so a group's root is its lowest member.
void unite(std::vector<int32_t>& parent, int32_t a, int32_t b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a == b) return;
  if (a < b)
    parent[b] = a;
  else
    parent[a] = b;
}

// CSR from (key, value) pairs with keys in [0, keys): values keep their input order within a key.
void build_csr(size_t keys, std::span<const int32_t> key_of, std::vector<int32_t>& offsets,
               std::vector<int32_t>& values, std::span<const int32_t> value_of) {
  offsets.assign(keys + 1, 0);
  for (int32_t k : key_of) ++offsets[k + 1];
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  values.resize(key_of.size());
  std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
  for (size_t i = 0; i < key_of.size(); ++i) values[fill[key_of[i]]++] = value_of[i];
}

}  // namespace

MeshConversion::MeshConversion(const SolidTopology& topology)
    : tet_nodes_(topology.tet_nodes),
      joint_nodes_(topology.joint_nodes),
      joint_tets_(topology.joint_tets),
      node_vertex_in_(topology.node_vertex) {
  const size_t nodes = topology.node_vertex.size(), joints = topology.joint_tets.size() / 2;
  build_indices(topology);
  intact_.assign(joints, 1);
  copy_vertex_.assign(nodes, -1);
  vertex_source_.reserve(nodes);
  for (size_t v = 0; v < topology.input_vertex_count; ++v) regroup(static_cast<int32_t>(v), true);
  tet_vertices_.resize(tet_nodes_.size());
  for (size_t i = 0; i < tet_nodes_.size(); ++i) tet_vertices_[i] = copy_vertex_[tet_nodes_[i]];
  build_surface(topology);
  vertex_x_.reserve(3 * nodes);
  vertex_v_.reserve(3 * nodes);
  vertex_mass_.reserve(nodes);
}

void MeshConversion::build_indices(const SolidTopology& topology) {
  const size_t nodes = topology.node_vertex.size();
  std::vector<int32_t> node_ids(nodes);
  std::iota(node_ids.begin(), node_ids.end(), 0);
  build_csr(topology.input_vertex_count, topology.node_vertex, copy_offsets_, copies_, node_ids);

  // (joint, corner) incidences per input vertex, in joint order: corner i ties node i to node i + 3.
  const size_t joints = joint_tets_.size() / 2;
  std::vector<int32_t> key(3 * joints), value(3 * joints);
  for (size_t j = 0; j < joints; ++j)
    for (int i = 0; i < 3; ++i) {
      key[3 * j + i] = topology.node_vertex[joint_nodes_[6 * j + i]];
      value[3 * j + i] = static_cast<int32_t>(3 * j + i);
    }
  std::vector<int32_t> packed;
  build_csr(topology.input_vertex_count, key, incidence_offsets_, packed, value);
  incidence_joint_.resize(packed.size());
  incidence_local_.resize(packed.size());
  for (size_t v = 0; v < topology.input_vertex_count; ++v) {
    const int32_t* first = &copies_[copy_offsets_[v]];
    const int32_t* last = &copies_[copy_offsets_[v + 1]];
    if (last - first > 65535)
      throw Error("mesh conversion: input vertex " + std::to_string(v) + " has " +
                  std::to_string(last - first) + " node copies; at most 65535 are supported");
    auto local = [&](int32_t node) {
      return static_cast<uint16_t>(std::lower_bound(first, last, node) - first);
    };
    for (int32_t k = incidence_offsets_[v]; k < incidence_offsets_[v + 1]; ++k) {
      const int32_t j = packed[k] / 3, c = packed[k] % 3;
      incidence_joint_[k] = j;
      incidence_local_[k] = {local(joint_nodes_[6 * j + c]), local(joint_nodes_[6 * j + c + 3])};
    }
  }

  std::vector<int32_t> tet_of(tet_nodes_.size());
  for (size_t i = 0; i < tet_of.size(); ++i) tet_of[i] = static_cast<int32_t>(i / 4);
  build_csr(nodes, tet_nodes_, node_tet_offsets_, node_tets_, tet_of);

  size_t most = 1;
  for (size_t v = 0; v < topology.input_vertex_count; ++v)
    most = std::max<size_t>(most, copy_offsets_[v + 1] - copy_offsets_[v]);
  parent_.resize(most);
}

void MeshConversion::build_surface(const SolidTopology& topology) {
  const size_t tets = tet_nodes_.size() / 4, joints = joint_tets_.size() / 2;
  // Faces by input vertices: seen once means external. Joint faces are seen twice (both tets).
  std::unordered_map<FaceKey, int32_t, FaceKeyHash> open;  // face -> 4 * tet + local face
  open.reserve(2 * tets);
  for (size_t e = 0; e < tets; ++e)
    for (int f = 0; f < 4; ++f) {
      std::array<int32_t, 3> v;
      for (int i = 0; i < 3; ++i) v[i] = topology.node_vertex[tet_nodes_[4 * e + kTetFaceCorners[f][i]]];
      const auto [it, inserted] = open.try_emplace(face_key(v), static_cast<int32_t>(4 * e + f));
      if (inserted) continue;
      if (it->second < 0)
        throw Error("mesh conversion: the face with input vertices " + std::to_string(v[0]) + ", " +
                    std::to_string(v[1]) + ", " + std::to_string(v[2]) +
                    " is shared by more than two tetrahedra; the solid mesh is not a valid tet mesh");
      it->second = -1;  // interior
    }
  std::unordered_set<FaceKey, FaceKeyHash> notch;
  for (const auto& t : topology.notch_triangles) notch.insert(face_key(t));

  tet_face_triangle_.assign(4 * tets, -1);
  // External faces in tet order, so the surface does not depend on the hash map's iteration order.
  size_t external = 0;
  std::vector<uint8_t> is_external(4 * tets, 0);
  for (const auto& [face, slot] : open)
    if (slot >= 0) is_external[slot] = 1, ++external;
  const size_t capacity = external + 2 * joints;
  tri_vertices_.reserve(3 * capacity);
  tri_nodes_.reserve(3 * capacity);
  tri_tag_.reserve(capacity);
  tri_time_.reserve(capacity);
  tri_joint_.reserve(capacity);
  for (size_t slot = 0; slot < 4 * tets; ++slot) {
    if (!is_external[slot]) continue;
    const int32_t e = static_cast<int32_t>(slot / 4);
    const int f = static_cast<int>(slot % 4);
    std::array<int32_t, 3> v;
    for (int i = 0; i < 3; ++i) v[i] = topology.node_vertex[tet_nodes_[4 * e + kTetFaceCorners[f][i]]];
    add_triangle(e, f, notch.count(face_key(v)) ? SurfaceTag::notch : SurfaceTag::boundary, -1.0, -1);
  }
  external_triangles_ = external;
}

void MeshConversion::add_triangle(int32_t tet, int face, SurfaceTag tag, double time, int32_t joint) {
  const int32_t t = static_cast<int32_t>(tri_tag_.size());
  for (int i = 0; i < 3; ++i) {
    const int32_t node = tet_nodes_[4 * tet + kTetFaceCorners[face][i]];
    tri_nodes_.push_back(node);
    tri_vertices_.push_back(copy_vertex_[node]);
  }
  tri_tag_.push_back(tag);
  tri_time_.push_back(time);
  tri_joint_.push_back(joint);
  tet_face_triangle_[4 * tet + face] = t;
}

void MeshConversion::refresh_triangle(int32_t t) {
  for (int i = 0; i < 3; ++i) tri_vertices_[3 * t + i] = copy_vertex_[tri_nodes_[3 * t + i]];
}

void MeshConversion::set_copy_vertex(int32_t copy, int32_t vertex) {
  copy_vertex_[copy] = vertex;
  if (tet_vertices_.empty()) return;  // still building
  for (int32_t k = node_tet_offsets_[copy]; k < node_tet_offsets_[copy + 1]; ++k) {
    const int32_t e = node_tets_[k];
    for (int c = 0; c < 4; ++c) {
      if (tet_nodes_[4 * e + c] != copy) continue;
      tet_vertices_[4 * e + c] = vertex;
      for (int f = 0; f < 4; ++f)  // the three faces that hold corner c
        if (f != c && tet_face_triangle_[4 * e + f] >= 0) refresh_triangle(tet_face_triangle_[4 * e + f]);
    }
  }
}

void MeshConversion::regroup(int32_t v, bool assign_all) {
  const int32_t begin = copy_offsets_[v], count = copy_offsets_[v + 1] - begin;
  if (count == 0) return;  // an input vertex no tet uses
  const int32_t* copy = &copies_[begin];
  for (int32_t i = 0; i < count; ++i) parent_[i] = i;
  for (int32_t k = incidence_offsets_[v]; k < incidence_offsets_[v + 1]; ++k)
    if (intact_[incidence_joint_[k]]) unite(parent_, incidence_local_[k][0], incidence_local_[k][1]);
  // Leaders (roots) come in ascending order. At build every group gets the next id. On update, the
  // first group met with a given old id keeps it; later ones with the same old id split off.
  for (int32_t i = 0; i < count; ++i) {
    const int32_t root = find_root(parent_, i);
    if (root != i) continue;
    if (assign_all) {
      copy_vertex_[copy[i]] = static_cast<int32_t>(vertex_source_.size());
      vertex_source_.push_back(v);
      continue;
    }
    const int32_t old = copy_vertex_[copy[i]];
    bool seen = false;
    for (int32_t p = 0; p < i && !seen; ++p) seen = parent_[p] == p && copy_vertex_[copy[p]] == old;
    if (!seen) continue;
    const int32_t fresh = static_cast<int32_t>(vertex_source_.size());
    vertex_source_.push_back(v);
    for (int32_t m = i; m < count; ++m)
      if (find_root(parent_, m) == i) set_copy_vertex(copy[m], fresh);
  }
  if (assign_all)
    for (int32_t i = 0; i < count; ++i) copy_vertex_[copy[i]] = copy_vertex_[copy[find_root(parent_, i)]];
}

bool MeshConversion::break_joint(int32_t joint, double time) {
  if (!intact_[joint]) return false;
  intact_[joint] = 0;
  ++broken_joints_;
  const int32_t* corners = &joint_nodes_[6 * joint];
  for (int side = 0; side < 2; ++side) {
    const int32_t tet = joint_tets_[2 * joint + side];
    add_triangle(tet, face_holding(&tet_nodes_[4 * tet], corners + 3 * side), SurfaceTag::fracture, time,
                 joint);
  }
  for (int i = 0; i < 3; ++i) regroup(node_vertex_in_[corners[i]], false);
  return true;
}

void MeshConversion::update_kinematics(std::span<const double> x, std::span<const double> v,
                                       std::span<const double> mass) {
  const size_t n = vertex_count();
  vertex_x_.resize(3 * n);
  vertex_v_.resize(3 * n);
  vertex_mass_.resize(n);
  const size_t inputs = copy_offsets_.size() - 1;
  // Each input vertex's copies map to vertices no other input vertex has, so blocks write disjoint rows.
  parallel_for(inputs, 1024, [&](size_t begin, size_t end) {
    for (size_t iv = begin; iv < end; ++iv) {
      for (int32_t k = copy_offsets_[iv]; k < copy_offsets_[iv + 1]; ++k) {
        const int32_t w = copy_vertex_[copies_[k]];
        vertex_mass_[w] = 0.0;
        for (int c = 0; c < 3; ++c) vertex_x_[3 * w + c] = vertex_v_[3 * w + c] = 0.0;
      }
      for (int32_t k = copy_offsets_[iv]; k < copy_offsets_[iv + 1]; ++k) {
        const int32_t node = copies_[k], w = copy_vertex_[node];
        const double m = mass[node];
        vertex_mass_[w] += m;
        for (int c = 0; c < 3; ++c) {
          vertex_x_[3 * w + c] += m * x[3 * node + c];
          vertex_v_[3 * w + c] += m * v[3 * node + c];
        }
      }
    }
  });
  // Divide once per vertex (a vertex's copies all belong to one input vertex, so the sums are complete).
  parallel_for(n, 4096, [&](size_t begin, size_t end) {
    for (size_t w = begin; w < end; ++w) {
      const double m = vertex_mass_[w];
      const double inv = m > 0 ? 1.0 / m : 0.0;
      for (int c = 0; c < 3; ++c) {
        vertex_x_[3 * w + c] *= inv;
        vertex_v_[3 * w + c] *= inv;
      }
    }
  });
}

size_t MeshConversion::fragment_count() const {
  std::vector<int32_t> parent(vertex_count());
  std::iota(parent.begin(), parent.end(), 0);
  const size_t tets = tet_vertices_.size() / 4;
  for (size_t e = 0; e < tets; ++e)
    for (int c = 1; c < 4; ++c) unite(parent, tet_vertices_[4 * e], tet_vertices_[4 * e + c]);
  std::vector<uint8_t> used(vertex_count(), 0);
  for (int32_t w : tet_vertices_) used[w] = 1;
  size_t fragments = 0;
  for (size_t w = 0; w < parent.size(); ++w) fragments += used[w] && find_root(parent, w) == int32_t(w);
  return fragments;
}

size_t MeshConversion::fracture_surface_count() const {
  std::vector<int32_t> broken;
  for (size_t j = 0; j < intact_.size(); ++j)
    if (!intact_[j]) broken.push_back(static_cast<int32_t>(j));
  std::vector<int32_t> parent(broken.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::unordered_map<uint64_t, int32_t> edge_owner;
  for (size_t b = 0; b < broken.size(); ++b)
    for (int i = 0; i < 3; ++i) {
      int64_t a = node_vertex_in_[joint_nodes_[6 * broken[b] + i]];
      int64_t c = node_vertex_in_[joint_nodes_[6 * broken[b] + (i + 1) % 3]];
      if (a > c) std::swap(a, c);
      const auto [it, inserted] =
          edge_owner.try_emplace(static_cast<uint64_t>(a) << 32 | static_cast<uint64_t>(c), int32_t(b));
      if (!inserted) unite(parent, it->second, static_cast<int32_t>(b));
    }
  size_t surfaces = 0;
  for (size_t b = 0; b < parent.size(); ++b) surfaces += find_root(parent, b) == int32_t(b);
  return surfaces;
}

}  // namespace rift
