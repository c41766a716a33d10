#pragma once
// A linear tet's geometry from its corners, written once for every kernel that needs it: the solid's
// reference shape (tet_prepare), the fluid's P1 gradients (fluid_element), the contact potential's
// barycentric frame, the exact tet-tet intersection (tet_intersection) and the contact's set-up constants.
//
// With the edges e_s = x_{s+1} - x_0 as the columns of J (the map from the reference tet),
//   det J = e_0 . (e_1 x e_2) = 6 V (signed: positive for a right-handed corner order),
//   J^-1 = cof(J)^T / det J, whose rows are e_1 x e_2, e_2 x e_0, e_0 x e_1 divided by det J:
// the gradients of the barycentric coordinates N_1, N_2, N_3 (and grad N_0 = -(their sum)).
// One expression for all of them, so each quantity has the same rounding wherever it is computed.
#include <cmath>

#include "kernels/vec3_ops.hpp"

namespace rift::kernels {

// e[s] = x_{s+1} - x_0 from four corners given by pointers (rows of a node table, or a corner array).
inline void tet_edges(const double* const corner[4], double e[3][3]) {
  for (int s = 0; s < 3; ++s)
    for (int d = 0; d < 3; ++d) e[s][d] = corner[s + 1][d] - corner[0][d];
}

inline void tet_edges(const double corner[4][3], double e[3][3]) {
  const double* const p[4] = {corner[0], corner[1], corner[2], corner[3]};
  tet_edges(p, e);
}

// The rows of det J * J^-1 (e_1 x e_2, e_2 x e_0, e_0 x e_1); returns det J = 6 V, signed.
inline double tet_inverse_rows(const double e[3][3], double rows[3][3]) {
  cross(e[1], e[2], rows[0]);
  cross(e[2], e[0], rows[1]);
  cross(e[0], e[1], rows[2]);
  return dot(e[0], rows[0]);
}

// det J = e_0 . (e_1 x e_2) = 6 V, signed.
inline double tet_six_volume(const double e[3][3]) {
  double row[3];
  cross(e[1], e[2], row);
  return dot(e[0], row);
}

// |det J| / 6 >= 0 from the four corners.
inline double tet_volume(const double corner[4][3]) {
  double e[3][3];
  tet_edges(corner, e);
  return std::fabs(tet_six_volume(e)) / 6.0;
}

}  // namespace rift::kernels
