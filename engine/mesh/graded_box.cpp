#include "engine/mesh/graded_box.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/mesh/box_faces.hpp"
#include "engine/mesh/surface_distance.hpp"

namespace rift {
namespace {

// A boundary triangle lies on a face of the box (box_faces.hpp).
int32_t classify(const GradedBoxSpec& spec, const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
  const int32_t face = box_face_of(spec.lo, spec.hi, mesh, tri);
  if (face < 0) throw Error("graded box: internal error, a boundary triangle lies on no face of the box");
  return face;
}

// The mesher puts the boundary's vertices on the box's faces to its own tolerance (4e-10 m off a face of a
// 0.1 m box is seen): each vertex of a triangle on a face goes exactly onto that face's plane, so that two
// meshes of the box cover the same points and a remesh finds every new node inside the old mesh.
void snap_to_box(const GradedBoxSpec& spec, TetMesh& mesh) {
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const int32_t face = mesh.triangle_surface[f];
    const size_t axis = static_cast<size_t>(face / 2);
    const double plane = face % 2 ? spec.hi[axis] : spec.lo[axis];
    for (const int32_t v : mesh.triangles[f]) mesh.nodes[static_cast<size_t>(v)][axis] = plane;
  }
}

}  // namespace

TetMesh generate_graded_box(const GradedBoxSpec& spec, std::span<const double> surface, Mesh3Stats* stats) {
  for (int d = 0; d < 3; ++d)
    if (!(spec.hi[d] > spec.lo[d]))
      throw Error("graded box: the box must have a positive extent on every axis");
  if (!(spec.size_min > 0.0) || !(spec.size_max >= spec.size_min) || !(spec.grading > 0.0))
    throw Error("graded box: need 0 < size_min <= size_max and grading > 0");
  const SurfaceDistance distance(surface);
  PolyhedralMeshInput in;
  const std::vector<std::array<double, 2>> rectangle = {
      {spec.lo[0], spec.lo[1]}, {spec.hi[0], spec.lo[1]}, {spec.hi[0], spec.hi[1]}, {spec.lo[0], spec.hi[1]}};
  in.patches.push_back(extruded_polygon(rectangle, spec.lo[2], spec.hi[2], [](double s, double t, double w) {
    return Vec3{s, t, w};
  }));
  in.feature_angle_deg = 1.0;  // the box's edges turn by 90 degrees, its coplanar triangles by round-off
  in.size = [&](const Vec3& p) {
    return std::min(spec.size_max, spec.size_min + spec.grading * distance(p));
  };
  in.seed = spec.seed;
  in.max_tets = spec.max_tets;
  in.max_tets_key = spec.max_tets_key;
  in.surface_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  in.classify = [&](const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
    return classify(spec, mesh, tri);
  };
  TetMesh mesh = mesh_polyhedron(in, stats);
  snap_to_box(spec, mesh);
  return mesh;
}

}  // namespace rift
