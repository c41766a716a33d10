#pragma once
// Mesh conversion (Guo et al. 2015, section 4.2 and Fig. 4): the solid's discontinuous mesh (tets with
// private nodes, tied by joints) seen as the continuous meshes a fluid needs.
//
// Continuous volume mesh. The node copies of one input vertex that are tied through intact joints are
// one vertex. Joints only ever tie copies of the same input vertex (corner i and i + 3), so the grouping
// is local: the copies of input vertex v fall into the connected components of v's star through its
// intact joints, and each component is one vertex. A crack front that ends inside the solid therefore
// keeps its vertices shared (the tets around a front edge are still tied around it), and a vertex whose
// copies fall into several groups is split into one vertex per group. Shared nodes (outside a fracture
// zone) are a single copy already. A vertex's position is the mass-weighted mean of its copies, its
// velocity the momentum-weighted mean (so the conversion conserves mass and momentum exactly).
//
// Continuous surface mesh. Every external face (a tet face no other tet shares) plus both faces of
// every broken joint, each oriented outward from its own tet, on the vertices above. Tags: outer boundary,
// pre-existing notch (external faces on the caller's notch triangles), new fracture (with the time it
// broke). The surface is closed and consistently oriented by construction: around every edge the faces
// pair off as the two ends of each run of tets tied around that edge. It is 2-manifold wherever the
// geometry is; it is not only where one piece of solid touches itself along an edge or at a point
// (two runs of one group around an edge), which the counters below report.
//
// Incremental. After the build an update costs O(copies around the 3 vertices of each newly broken
// joint), independent of the mesh size: a joint's break appends its two faces and regroups its three
// vertices. A group that splits keeps its vertex id for the part holding its lowest copy; the other
// parts get new ids at the end. Ids therefore depend on the order of the breaks only, never on how they
// are batched, so replaying the fracture log in order (a restart) rebuilds the same numbering. Capacity
// is reserved at build time (vertices <= copies, triangles <= external + 2 joints): updates allocate
// nothing.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rift {

enum class SurfaceTag : uint8_t { boundary = 0, notch = 1, fracture = 2 };

// The solid's topology as the conversion reads it (spans into the solid's tables or a test's arrays).
struct SolidTopology {
  size_t input_vertex_count = 0;
  std::span<const int32_t> node_vertex;  // 1 per solid node: the input vertex it copies
  std::span<const int32_t> tet_nodes;    // 4 per tet, positively oriented
  std::span<const int32_t> joint_nodes;  // 6 per joint: corners 0-2 on tet A, 3-5 their copies on tet B
  std::span<const int32_t> joint_tets;   // 2 per joint: (A, B)
  // External faces that lie on these triangles (input vertex ids, any order) are tagged notch.
  std::span<const std::array<int32_t, 3>> notch_triangles;
};

class MeshConversion {
 public:
  // Builds both meshes with every joint intact. Throws rift::Error if a face is shared by more than two
  // tets (not a valid tet mesh).
  explicit MeshConversion(const SolidTopology& topology);

  // Joint j broke at `time`: its two faces join the surface and its three vertices are regrouped.
  // A joint already broken is ignored (returns false).
  bool break_joint(int32_t joint, double time);

  // Vertex positions and velocities from the copies' (x, v, mass), 3 values per node for x and v:
  // mass-weighted means. Parallel over input vertices; the result is the same on any thread count.
  void update_kinematics(std::span<const double> x, std::span<const double> v, std::span<const double> mass);

  // The continuous volume mesh.
  size_t vertex_count() const { return vertex_source_.size(); }
  std::span<const int32_t> node_vertex() const { return copy_vertex_; }      // per solid node
  std::span<const int32_t> tet_vertices() const { return tet_vertices_; }    // 4 per tet
  std::span<const int32_t> vertex_source() const { return vertex_source_; }  // input vertex per vertex
  std::span<const double> vertex_x() const { return vertex_x_; }             // after update_kinematics
  std::span<const double> vertex_v() const { return vertex_v_; }
  std::span<const double> vertex_mass() const { return vertex_mass_; }

  // The continuous surface mesh (triangles in the order they joined: external faces, then broken
  // joints' faces, side A then side B, in the order of the breaks).
  size_t triangle_count() const { return tri_tag_.size(); }
  std::span<const int32_t> triangle_vertices() const { return tri_vertices_; }  // 3 per triangle, outward
  std::span<const int32_t> triangle_nodes() const { return tri_nodes_; }        // the same on solid nodes
  std::span<const SurfaceTag> triangle_tag() const { return tri_tag_; }
  std::span<const double> triangle_time() const { return tri_time_; }     // -1 for external faces
  std::span<const int32_t> triangle_joint() const { return tri_joint_; }  // -1 for external faces
  size_t external_triangle_count() const { return external_triangles_; }

  bool joint_intact(int32_t joint) const { return intact_[joint] != 0; }
  size_t broken_joint_count() const { return broken_joints_; }
  // Changes with every break: consumers (output, the fluid) redo what depends on the topology.
  uint64_t revision() const { return broken_joints_; }

  // Connected pieces of solid: components of the tets through shared vertices (O(mesh), on demand).
  size_t fragment_count() const;
  // Fracture surfaces: components of the broken joints through shared input edges (O(broken joints)).
  size_t fracture_surface_count() const;

 private:
  void build_indices(const SolidTopology& topology);
  void build_surface(const SolidTopology& topology);
  // Groups the copies of input vertex v through its intact joints; with assign_all every group gets a
  // new id (the build), else only the parts split off an existing vertex do.
  void regroup(int32_t v, bool assign_all);
  void add_triangle(int32_t tet, int face, SurfaceTag tag, double time, int32_t joint);
  void refresh_triangle(int32_t triangle);
  void set_copy_vertex(int32_t copy, int32_t vertex);

  std::span<const int32_t> tet_nodes_, joint_nodes_, joint_tets_, node_vertex_in_;
  // Per input vertex: its copies (ascending) and its joint incidences, as CSR. An incidence is a joint
  // and the two copies it ties, as positions in the vertex's copy list (found once, at build).
  std::vector<int32_t> copy_offsets_, copies_, incidence_offsets_, incidence_joint_;
  std::vector<std::array<uint16_t, 2>> incidence_local_;
  // Per solid node: the tets that use it, as CSR (one tet for a private copy).
  std::vector<int32_t> node_tet_offsets_, node_tets_;
  std::vector<int32_t> copy_vertex_, vertex_source_, tet_vertices_;
  std::vector<int32_t> tet_face_triangle_;  // 4 per tet: the surface triangle on that face, or -1
  std::vector<uint8_t> intact_;
  std::vector<int32_t> tri_vertices_, tri_nodes_, tri_joint_;
  std::vector<SurfaceTag> tri_tag_;
  std::vector<double> tri_time_;
  std::vector<double> vertex_x_, vertex_v_, vertex_mass_;
  std::vector<int32_t> parent_;  // scratch: local union-find over one vertex's copies
  size_t external_triangles_ = 0, broken_joints_ = 0;
};

}  // namespace rift
