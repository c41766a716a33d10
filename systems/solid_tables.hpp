#pragma once
// The solid's tables and their columns: each column is declared here once, as a ColumnRef
// (engine/core/column_ref.hpp) that set-up creates it from and systems look it up and declare access
// through. A table's columns are listed in the order they are created, the order the state hash runs.
#include <cstdint>
#include <string>

#include "engine/core/column_ref.hpp"

namespace rift::solid {

inline constexpr const char* node_table = "solid_node";
inline constexpr const char* tet_table = "solid_tet";
inline constexpr const char* joint_table = "solid_joint";
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

// solid_node's columns of the contact (with contact only).
namespace node {
inline constexpr ColumnRef<double, 3> x_detect{node_table, "x_detect"};  // positions at the last detection
}  // namespace node

// solid_tet: one row per tet, created in this order.
namespace tet {
inline constexpr ColumnRef<int32_t, 4> nodes{tet_table, "nodes"};
inline constexpr ColumnRef<double, 9> dm_inv{tet_table, "dm_inv"};  // inverse of the reference edge matrix
inline constexpr ColumnRef<double> volume0{tet_table, "volume0"};
inline constexpr ColumnRef<int32_t> material{tet_table, "material"};
inline constexpr ColumnRef<int32_t> region{tet_table, "region"};
inline constexpr ColumnRef<double, 12> corner_force{tet_table, "corner_force"};
inline constexpr ColumnRef<double, 6> stress{tet_table, "stress"};  // Cauchy: xx yy zz xy yz zx
inline constexpr ColumnRef<double> energy{tet_table, "energy"};     // elastic strain energy [J]
inline constexpr ColumnRef<double> viscous_power{tet_table, "viscous_power"};
}  // namespace tet

// solid_joint (only with a fracture zone), created in this order.
namespace joint {
inline constexpr ColumnRef<int32_t, 6> nodes{joint_table, "nodes"};
inline constexpr ColumnRef<int32_t, 2> tets{joint_table, "tets"};
inline constexpr ColumnRef<int32_t> material{joint_table, "material"};           // the joint material
inline constexpr ColumnRef<double, kVariableWidth> d_max{joint_table, "d_max"};  // one per integration point
// 0 intact, 1 tensile, 2 shear, 3 initial crack
inline constexpr ColumnRef<uint8_t> broken{joint_table, "broken"};
// the forces on side B's corners; side A's are minus these
inline constexpr ColumnRef<double, 9> corner_force{joint_table, "corner_force"};
inline constexpr ColumnRef<double> opening{joint_table, "opening"};
inline constexpr ColumnRef<double> slip{joint_table, "slip"};
inline constexpr ColumnRef<double> damage{joint_table, "damage"};
inline constexpr ColumnRef<double> stored_energy{joint_table, "stored_energy"};
// the in-situ state's offset (0 without one)
inline constexpr ColumnRef<double, 3> initial_offset{joint_table, "initial_offset"};
// 3 per integration point, only when a joint material has residual friction
inline constexpr ColumnRef<double, kVariableWidth> residual_anchor{joint_table, "residual_anchor"};
inline constexpr ColumnRef<uint8_t> in_contact{joint_table, "in_contact"};  // with contact only
}  // namespace joint

namespace joint_state {
// the integration points that have begun to soften so far
inline constexpr ColumnRef<int64_t> damage_onsets{joint_state_table, "damage_onsets"};
}  // namespace joint_state

// solid_load_face: one row per loaded boundary face.
namespace face {
inline constexpr ColumnRef<int32_t, 3> nodes{face_table, "nodes"};
inline constexpr ColumnRef<int32_t> load{face_table, "load"};  // its boundary condition
inline constexpr ColumnRef<double, 9> corner_force{face_table, "corner_force"};
// with wetted faces (fluid_solid.force: wetted_faces): the fluid's pressure at the face's centroid, held
// over a window of solid steps [Pa]; the fluid-solid coupling creates and writes it
inline constexpr ColumnRef<double> fluid_pressure{face_table, "fluid_pressure"};
}  // namespace face

// solid_fracture_event: one row per broken joint, in the order they broke.
namespace event {
inline constexpr ColumnRef<int64_t> step{event_table, "step"};
inline constexpr ColumnRef<double> time{event_table, "time"};
inline constexpr ColumnRef<int32_t> joint{event_table, "joint"};
inline constexpr ColumnRef<uint8_t> mode{event_table, "mode"};  // as joint::broken
inline constexpr ColumnRef<double, 3> centroid{event_table, "centroid"};
inline constexpr ColumnRef<double, 3> normal{event_table, "normal"};
inline constexpr ColumnRef<double> area{event_table, "area"};
// what the joint stored when it broke [J]: handed over, not dissipated; 0 for initial cracks
inline constexpr ColumnRef<double> released_energy{event_table, "released_energy"};
}  // namespace event

// solid_energy: one row of running integrals [J].
namespace energy {
// loads, gravity, prescribed motion
inline constexpr ColumnRef<double> external_work{energy_table, "external_work"};
inline constexpr ColumnRef<double> tet_work{energy_table, "tet_work"};  // of the tets' forces on the nodes
inline constexpr ColumnRef<double> joint_work{energy_table, "joint_work"};        // of the joints' forces
inline constexpr ColumnRef<double> damping{energy_table, "damping"};              // viscous dissipation
inline constexpr ColumnRef<double> joint_energy0{energy_table, "joint_energy0"};  // stored at t = 0
inline constexpr ColumnRef<double> kinetic0{energy_table, "kinetic0"};  // from solid.initial_velocity
// with contact only
inline constexpr ColumnRef<double> contact_work{energy_table, "contact_work"};
inline constexpr ColumnRef<double> friction{energy_table, "friction"};
inline constexpr ColumnRef<double> contact_damping{energy_table, "contact_damping"};
}  // namespace energy

// solid_contact_pair (with contact only): one row per candidate pair of the last detection, sorted.
namespace contact_pair {
inline constexpr ColumnRef<int32_t, 2> tets{contact_pair_table, "tets"};       // a < b
inline constexpr ColumnRef<double, 3> history{contact_pair_table, "history"};  // friction force on a
inline constexpr ColumnRef<double, 24> force{contact_pair_table, "force"};     // corner forces of a then b
// of the last step
inline constexpr ColumnRef<double> friction_dissipation{contact_pair_table, "friction_dissipation"};
inline constexpr ColumnRef<double> damping_dissipation{contact_pair_table, "damping_dissipation"};
}  // namespace contact_pair

namespace contact_state {
inline constexpr ColumnRef<int64_t> detections{contact_state_table, "detections"};  // detections so far
}  // namespace contact_state

// solid_force_slot's slot: the corner-force slots of every node, grouped by node: tet corners [0, 4 T), then
// joint corners [4 T, 4 T + 6 J) (corner i of joint j at 4 T + 2 (3 j + i mod 3) + (i < 3):
// kernels::ForceSlots's pairs), then loaded-face corners.

inline std::string col(const char* table, const char* column) {
  return std::string(table) + "." + column;
}

}  // namespace rift::solid
