#pragma once
// Distributed loads on boundary triangles, lumped to their corners (each gets a third).
// Pressure acts against the current outward normal (a follower load); traction is a force per unit
// current area in a fixed direction.
#include <cstdint>
#include <span>

namespace rift::kernels {

struct FaceLoad {
  double pressure;     // [Pa], positive pushes into the body
  double traction[3];  // [Pa]
};

// x: 3 per node; face_nodes: 3 per face, ordered so (x1-x0)x(x2-x0) points out of the body;
// face_load: per face, index into loads; corner_force: out, 9 per face.
void surface_loads(std::span<const double> x, std::span<const int32_t> face_nodes,
                   std::span<const int32_t> face_load, std::span<const FaceLoad> loads,
                   std::span<double> corner_force, size_t begin, size_t end);

}  // namespace rift::kernels
