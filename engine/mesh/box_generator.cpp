// Box generator on CGAL Mesh_3 through polyhedral_mesher (see box_generator.hpp for the contract).
#include "engine/mesh/box_generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/mesh/box_faces.hpp"
#include "engine/mesh/notched_box.hpp"
#include "engine/mesh/polyhedral_mesher.hpp"

namespace rift {
namespace {

// Any normal turn above this marks a prism edge as a feature; the polygon turns by >= 5 degrees at
// every vertex (checked in make_notched_box) and coplanar triangles turn by round-off only.
constexpr double kFeatureAngleDeg = 1.0;

// Which named surface a boundary triangle lies on: a box face (box_faces.hpp), otherwise the notch whose
// faces pass nearest to the triangle's centroid.
int32_t classify(const NotchedBox& box, const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
  if (const int32_t face = box_face_of(box.lo, box.hi, mesh, tri); face >= 0) return face;
  Vec3 c{0, 0, 0};
  for (const int32_t v : tri)
    for (int k = 0; k < 3; ++k) c[k] += mesh.nodes[v][k] / 3;
  int32_t best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < box.notch_surface.size(); ++i) {
    const double d = distance_to_notches(box, c, static_cast<int>(i));
    if (d < best_d) best_d = d, best = box.notch_surface[i];
  }
  if (best < 0) {
    double off =
        std::numeric_limits<double>::infinity();  // distance of the farthest node from the nearest face
    for (int a = 0; a < 3; ++a)
      for (const double plane : {box.lo[a], box.hi[a]}) {
        double worst = 0;
        for (const int32_t v : tri) worst = std::max(worst, std::abs(mesh.nodes[v][a] - plane));
        off = std::min(off, worst);
      }
    throw Error(fmt::format(
        "mesh.generate: internal error, a boundary triangle at ({:.9g}, {:.9g}, {:.9g}) lies on no box face "
        "(its nodes are up to {:.3g} m off the nearest face plane) and there is no notch",
        c[0], c[1], c[2], off));
  }
  return best;
}

}  // namespace

TetMesh generate_box_mesh(const MeshGenerateSpec& spec, Mesh3Stats* stats) {
  const NotchedBox box = make_notched_box(spec);
  PolyhedralMeshInput in;
  in.patches.push_back(extruded_polygon(box.polygon, box.lo[box.axis[2]], box.hi[box.axis[2]],
                                        [&](double s, double t, double w) { return to_3d(box, s, t, w); }));
  in.feature_angle_deg = kFeatureAngleDeg;
  in.size = [&](const Vec3& p) { return mesh_size_at(spec, box, p); };
  in.seed = spec.seed;
  in.max_tets = spec.max_elements;
  in.max_tets_key = spec.max_elements_key;
  in.surface_names = box.surface_names;
  in.classify = [&](const TetMesh& mesh, const std::array<int32_t, 3>& tri) {
    return classify(box, mesh, tri);
  };
  return mesh_polyhedron(in, stats);
}

}  // namespace rift
