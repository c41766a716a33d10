#include "engine/mesh/discontinuous_mesh.hpp"

#include <algorithm>

#include "engine/core/error.hpp"
#include "engine/mesh/tet_faces.hpp"

namespace rift {

DiscontinuousMesh make_discontinuous(const TetMesh& mesh, const std::function<bool(size_t)>& in_zone) {
  DiscontinuousMesh out;
  const size_t nt = mesh.tets.size();
  out.tet_in_zone.resize(nt);
  for (size_t e = 0; e < nt; ++e) out.tet_in_zone[e] = in_zone(e) ? 1 : 0;

  // Shared nodes first (input vertices used by a tet outside the zone, in vertex order), then 4 private
  // nodes per zone tet in tet order: a zone tet's nodes are contiguous, which the tet kernel likes.
  std::vector<int32_t> shared_id(mesh.nodes.size(), -1);
  for (size_t e = 0; e < nt; ++e)
    if (!out.tet_in_zone[e])
      for (int32_t v : mesh.tets[e]) shared_id[v] = 0;
  for (size_t v = 0; v < mesh.nodes.size(); ++v)
    if (shared_id[v] == 0) {
      shared_id[v] = static_cast<int32_t>(out.nodes.size());
      out.nodes.push_back(mesh.nodes[v]);
      out.node_vertex.push_back(static_cast<int32_t>(v));
    }
  out.tets.resize(nt);
  for (size_t e = 0; e < nt; ++e)
    for (int k = 0; k < 4; ++k) {
      const int32_t v = mesh.tets[e][k];
      if (!out.tet_in_zone[e]) {
        out.tets[e][k] = shared_id[v];
        continue;
      }
      out.tets[e][k] = static_cast<int32_t>(out.nodes.size());
      out.nodes.push_back(mesh.nodes[v]);
      out.node_vertex.push_back(v);
    }

  // A joint on each face two tets share, one of them in the fracture zone.
  const OpenFaces open_faces =
      for_each_shared_face(mesh.tets, [&](int32_t a, int32_t fa, int32_t e, int32_t f) {
        if (!out.tet_in_zone[size_t(a)] && !out.tet_in_zone[size_t(e)]) return;
        // Corners 0-2: tet A's face reversed; 3-5: the copies in tet B of the same vertices.
        std::array<int32_t, 6> joint;
        for (int i = 0; i < 3; ++i) {
          const int corner = kTetFaceCorners[fa][2 - i];
          joint[i] = out.tets[a][corner];
          const int32_t vertex = mesh.tets[a][corner];
          int kb = 0;
          while (mesh.tets[e][kb] != vertex) ++kb;
          joint[3 + i] = out.tets[e][kb];
        }
        out.joints.push_back(joint);
        out.joint_tets.push_back({a, static_cast<int32_t>(e)});
        out.joint_faces.push_back({fa, f});
      });

  // Boundary triangles onto the copies of the tet they bound (the faces still open).
  out.triangles.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto it = open_faces.find(face_key(mesh.triangles[t]));
    if (it == open_faces.end())
      throw Error("mesh: surface triangle " + std::to_string(t) + " (vertices " +
                  std::to_string(mesh.triangles[t][0]) + ", " + std::to_string(mesh.triangles[t][1]) + ", " +
                  std::to_string(mesh.triangles[t][2]) +
                  ") is not a boundary face of the tetrahedra; surfaces must lie on the mesh boundary");
    const int32_t e = it->second.first;
    for (int i = 0; i < 3; ++i) {
      int k = 0;
      while (mesh.tets[e][k] != mesh.triangles[t][i]) ++k;
      out.triangles[t][i] = out.tets[e][k];
    }
  }
  return out;
}

}  // namespace rift
