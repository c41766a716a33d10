#pragma once
// Names of the solid's tables and columns, in one place, so systems declare access with the same
// strings the store uses.
#include <cstdint>
#include <string>

#include "engine/core/column_ref.hpp"

namespace rift::solid {

inline constexpr const char* node_table = "solid_node";
inline constexpr const char* tet_table = "solid_tet";
inline constexpr const char* joint_table = "solid_joint";
// One row: damage_onsets (int64), the integration points that have begun to soften so far.
inline constexpr const char* joint_state_table = "solid_joint_state";
inline constexpr const char* face_table = "solid_load_face";
inline constexpr const char* slot_table = "solid_force_slot";
inline constexpr const char* event_table = "solid_fracture_event";
inline constexpr const char* energy_table = "solid_energy";
inline constexpr const char* contact_pair_table = "solid_contact_pair";
inline constexpr const char* contact_state_table = "solid_contact_state";

// solid_node's columns that every solid scene has (the force columns of systems/node_force_route.hpp
// join them with their producers).
namespace node {
inline constexpr ColumnRef<double, 3> x0{node_table, "x0"};  // reference position
inline constexpr ColumnRef<double, 3> x{node_table, "x"};
inline constexpr ColumnRef<double, 3> v{node_table, "v"};  // at t - dt/2
inline constexpr ColumnRef<double, 3> f{node_table, "f"};  // total force of the last observed step
inline constexpr ColumnRef<double> mass{node_table, "mass"};
inline constexpr ColumnRef<double> inv_mass{node_table, "inv_mass"};  // 0 for a massless node
inline constexpr ColumnRef<uint8_t, 3> free{node_table, "free"};      // 1: integrated, 0: held
// the velocity condition holding each component, or -1 (velocity 0)
inline constexpr ColumnRef<int32_t, 3> held{node_table, "held"};
inline constexpr ColumnRef<int32_t, 2> slots{node_table, "slots"};  // [begin, end) in solid_force_slot
inline constexpr ColumnRef<int32_t> vertex{node_table, "vertex"};   // the input mesh vertex the node copies
}  // namespace node
inline constexpr ColumnRef<int32_t> slot{slot_table, "slot"};

// solid_tet: nodes (i32 x4), dm_inv (9), volume0 (1), material (i32), region (i32),
//            corner_force (12), stress (6), energy (1), viscous_power (1)
// solid_joint (only with a fracture zone): nodes (i32 x6), tets (i32 x2), material (i32, joint material),
//            d_max (points per joint), broken (u8: 0 intact, 1 tensile, 2 shear, 3 initial crack),
//            corner_force (9: the forces on side B's corners; side A's are minus these), opening, slip,
//            damage, stored_energy (1 each), initial_offset (3, in-situ state; 0 without one),
//            residual_anchor (3 per point, only when a joint material has residual friction) contact_force
//            (3, with contact only: the contact forces of the step, gathered per node), x_detect (3, with
//            contact only: positions at the last contact detection)
// solid_load_face: nodes (i32 x3), load (i32), corner_force (9)
// solid_force_slot: slot (i32): the corner-force slots of every node, grouped by node: tet corners
//            [0, 4 T), then joint corners [4 T, 4 T + 6 J) (corner i of joint j at 4 T + 2 (3 j + i mod 3)
//            + (i < 3): kernels::ForceSlots's pairs), then loaded-face corners
// solid_fracture_event: one row per broken joint, in the order they broke: step (i64), time, joint (i32),
//            mode (u8, as broken), centroid (3), normal (3), area, released_energy (what the joint stored
//            when it broke [J]: handed over, not dissipated; 0 for initial cracks)
// solid_energy: one row of running integrals [J]: external_work (loads, gravity, prescribed motion),
//            tet_work and joint_work (work done by those forces on the nodes), damping (viscous
//            dissipation), joint_energy0 (joint stored energy at t = 0, the in-situ state), kinetic0 (kinetic
//            energy at t = 0, from solid.initial_velocity); with contact
//            also contact_work (work of the contact forces), friction and contact_damping (dissipation)
// solid_contact_pair (with contact only): one row per candidate pair of the last detection, sorted:
//            tets (i32 x2, a < b), history (3, friction force on a), force (24, corner forces of a then b),
//            friction_dissipation, damping_dissipation (of the last step)
// solid_contact_state (with contact only): one row: detections (i64, detections so far)

inline std::string col(const char* table, const char* column) {
  return std::string(table) + "." + column;
}

}  // namespace rift::solid
