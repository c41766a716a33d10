#include "kernels/surface_load.hpp"

#include <cmath>

namespace rift::kernels {

void surface_loads(std::span<const double> x, std::span<const int32_t> face_nodes,
                   std::span<const int32_t> face_load, std::span<const FaceLoad> loads,
                   std::span<double> corner_force, size_t begin, size_t end,
                   std::span<const double> face_pressure) {
  for (size_t e = begin; e < end; ++e) {
    // The area vector n*A; a third of the load goes to each corner.
    double na[3];
    face_area_vector(x, face_nodes, e, na);
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
