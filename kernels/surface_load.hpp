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

// Half the cross product (x1 - x0) x (x2 - x0) of face f: its outward normal times its area [m^2].
inline void face_area_vector(std::span<const double> x, std::span<const int32_t> face_nodes, size_t f,
                             double na[3]) {
  const double* p0 = &x[3 * face_nodes[3 * f + 0]];
  const double* p1 = &x[3 * face_nodes[3 * f + 1]];
  const double* p2 = &x[3 * face_nodes[3 * f + 2]];
  const double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  na[0] = 0.5 * (a[1] * b[2] - a[2] * b[1]);
  na[1] = 0.5 * (a[2] * b[0] - a[0] * b[2]);
  na[2] = 0.5 * (a[0] * b[1] - a[1] * b[0]);
}

// x: 3 per node; face_nodes: 3 per face, ordered so (x1-x0)x(x2-x0) points out of the body;
// face_load: per face, index into loads; corner_force: out, 9 per face. face_pressure (1 per face, or
// empty): a pressure of the face's own added to its load's (the fluid's on a wetted face).
void surface_loads(std::span<const double> x, std::span<const int32_t> face_nodes,
                   std::span<const int32_t> face_load, std::span<const FaceLoad> loads,
                   std::span<double> corner_force, size_t begin, size_t end,
                   std::span<const double> face_pressure = {});

}  // namespace rift::kernels
