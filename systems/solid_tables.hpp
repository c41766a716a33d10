#pragma once
// Names of the solid's tables and columns, in one place, so systems declare access with the same
// strings the store uses.
#include <string>

namespace rift::solid {

inline constexpr const char* node_table = "solid_node";
inline constexpr const char* tet_table = "solid_tet";
inline constexpr const char* face_table = "solid_load_face";
inline constexpr const char* slot_table = "solid_force_slot";

// solid_node: x0 (3, reference position), x (3), v (3, at t - dt/2), f (3, total force of the last step),
// mass (1), inv_mass (1), free (u8 x3), held (i32, velocity condition or -1), slots (i32 x2: [begin, end) in
// solid_force_slot)
// solid_tet: nodes (i32 x4), dm_inv (9), volume0 (1), material (i32), region (i32),
//            corner_force (12), stress (6), energy (1)
// solid_load_face: nodes (i32 x3), load (i32), corner_force (9)
// solid_force_slot: slot (i32): the corner-force slots of every node, grouped by node

inline std::string col(const char* table, const char* column) {
  return std::string(table) + "." + column;
}

}  // namespace rift::solid
