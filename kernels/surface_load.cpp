#include "kernels/surface_load.hpp"

#include <cmath>

namespace rift::kernels {

void surface_loads(std::span<const double> x, std::span<const int32_t> face_nodes,
                   std::span<const int32_t> face_load, std::span<const FaceLoad> loads,
                   std::span<double> corner_force, size_t begin, size_t end,
                   std::span<const double> face_pressure) {
  for (size_t e = begin; e < end; ++e) {
    const double* p0 = &x[3 * face_nodes[3 * e + 0]];
    const double* p1 = &x[3 * face_nodes[3 * e + 1]];
    const double* p2 = &x[3 * face_nodes[3 * e + 2]];
    const double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    const double b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    // Half the cross product is the area vector n*A; a third of the load goes to each corner.
    const double na[3] = {0.5 * (a[1] * b[2] - a[2] * b[1]), 0.5 * (a[2] * b[0] - a[0] * b[2]),
                          0.5 * (a[0] * b[1] - a[1] * b[0])};
    const double area = std::sqrt(na[0] * na[0] + na[1] * na[1] + na[2] * na[2]);
    const FaceLoad& L = loads[face_load[e]];
    double f[3];
    const double* S = L.stress;
    const double sn[3] = {S[0] * na[0] + S[3] * na[1] + S[5] * na[2],
                          S[3] * na[0] + S[1] * na[1] + S[4] * na[2],
                          S[5] * na[0] + S[4] * na[1] + S[2] * na[2]};
    const double pressure = face_pressure.empty() ? L.pressure : L.pressure + face_pressure[e];
    for (int c = 0; c < 3; ++c) f[c] = (-pressure * na[c] + L.traction[c] * area + sn[c]) / 3.0;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) corner_force[9 * e + 3 * k + c] = f[c];
  }
}

}  // namespace rift::kernels
