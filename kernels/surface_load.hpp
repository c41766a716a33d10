#pragma once
// Distributed loads on boundary triangles, lumped to their corners (each gets a third).
// Pressure acts against the current outward normal (a follower load); traction is a force per unit
// current area in a fixed direction; a stress load applies the traction sigma . n of a fixed Cauchy tensor
// on the current outward normal (the boundary half of an in-situ stress state).
#include <cstdint>
#include <span>

namespace rift::kernels {

struct FaceLoad {
  double pressure;     // [Pa], positive pushes into the body
  double traction[3];  // [Pa]
  double stress[6];    // [Pa] xx yy zz xy yz zx; zero for no stress load
};

// x: 3 per node; face_nodes: 3 per face, ordered so (x1-x0)x(x2-x0) points out of the body;
// face_load: per face, index into loads; corner_force: out, 9 per face. face_pressure (1 per face, or
// empty): a pressure of the face's own added to its load's (the fluid's on a wetted face).
void surface_loads(std::span<const double> x, std::span<const int32_t> face_nodes,
                   std::span<const int32_t> face_load, std::span<const FaceLoad> loads,
                   std::span<double> corner_force, size_t begin, size_t end,
                   std::span<const double> face_pressure = {});

}  // namespace rift::kernels
