#pragma once
// The fracture flow's tables (systems/fracture_flow) and their columns, each declared once as a ColumnRef
// (engine/core/column_ref.hpp), in the order they are created.
#include <cstdint>

#include "engine/core/column_ref.hpp"

namespace rift::fracture_flow {

inline constexpr const char* vertex_table = "fracture_flow_vertex";
inline constexpr const char* books_table = "fracture_flow_books";
inline constexpr const char* joint_table = "fracture_flow_joint";

// fracture_flow_vertex: one row per input mesh vertex that any joint touches (fixed at set-up; the
// network's vertices are those of its wet triangles), plus the well's when the well is the notch's wall.
namespace vertex {
inline constexpr ColumnRef<int32_t> mesh_vertex{vertex_table, "mesh_vertex"};   // -1: the well's wall
inline constexpr ColumnRef<double> pressure{vertex_table, "pressure"};          // [Pa]
inline constexpr ColumnRef<double> mass{vertex_table, "mass"};                  // [kg]
inline constexpr ColumnRef<uint8_t> role{vertex_table, "role"};                 // FlowRole
inline constexpr ColumnRef<double> wetting_time{vertex_table, "wetting_time"};  // [s], -1 until fluid arrives
// [kg]: what a fixed vertex (the well under pressure control, a vent) has given the network so far;
// negative: taken
inline constexpr ColumnRef<double> exchanged{vertex_table, "exchanged"};
inline constexpr ColumnRef<double> volume{vertex_table, "volume"};  // the fluid's volume [m^3]
}  // namespace vertex

// fracture_flow_books: one row of running totals.
namespace books {
inline constexpr ColumnRef<double> injected{books_table,
                                            "injected"};           // [kg]: sources and the well's exchange
inline constexpr ColumnRef<double> vented{books_table, "vented"};  // [kg]
inline constexpr ColumnRef<double> leaked{books_table, "leaked"};  // [kg]
inline constexpr ColumnRef<double> dissipation{books_table, "dissipation"};  // [J]
inline constexpr ColumnRef<double> pump_work{books_table, "pump_work"};      // [J]
inline constexpr ColumnRef<double> fluid_work{books_table,
                                              "fluid_work"};  // [J]: the fluid's work on the rock
inline constexpr ColumnRef<double> initial_mass{books_table, "initial_mass"};  // [kg]
// [Pa]: the well's pressure when the surrounding fluid sets it (written by the fluid-solid coupling)
inline constexpr ColumnRef<double> inlet_pressure{books_table, "inlet_pressure"};
}  // namespace books

// fracture_flow_joint: one row per joint.
namespace joint {
// its place in the order the network took the joints in (-1: not in it), so a restart rebuilds the network
// in that order
inline constexpr ColumnRef<int64_t> joined{joint_table, "joined"};
}  // namespace joint

}  // namespace rift::fracture_flow
