#pragma once
// The fracture flow's tables (systems/fracture_flow):
// fracture_flow_vertex: one row per input mesh vertex that any joint touches (fixed at set-up; the
//   network's vertices are those of its wet triangles): mesh_vertex (i32), pressure [Pa], mass [kg],
//   role (u8, FlowRole), wetting_time [s] (-1 until fluid arrives), exchanged [kg] (what a fixed vertex,
//   the well under pressure control or a vent, has given the network so far; negative: taken)
// fracture_flow_joint: one row per joint: joined (i64), its place in the order the network took the joints
//   in (-1: not in it), so a restart rebuilds the network in that order
// fracture_flow_books: one row of running totals: injected [kg] (sources and the well's exchange),
//   vented [kg], leaked [kg], dissipation [J], pump_work [J], fluid_work [J] (the fluid's work on the
//   rock, sum of p dV), initial_mass [kg]
namespace rift::fracture_flow {

inline constexpr const char* vertex_table = "fracture_flow_vertex";
inline constexpr const char* books_table = "fracture_flow_books";
inline constexpr const char* joint_table = "fracture_flow_joint";

}  // namespace rift::fracture_flow
