#pragma once
// Columns the fluid-solid coupling (fluid_solid_model.hpp) adds to the store, so outputs, the state hash
// and checkpoints cover the exchange:
//
// fluid_tet (fluid_tables.hpp): solid_volume (1, |K ∩ Omega_s| [m^3]), solid_fraction (1, alpha_s),
//            solid_velocity (3, u_s,K the flow is relaxed to), absorption (1, sigma [kg/(m^3 s)]),
//            velocity_before (3, the mean fluid velocity of K at the start of the fluid step)
// solid_node (solid_tables.hpp): fluid_force (3, the fluid's force on the node, held over a window of
//            solid sub-steps [N]); with fluid_solid.added_mass: fluid_added_mass (1, the virtual mass [kg],
//            already in `mass`), window_velocity (3, v at the last exchange); with fluid_solid.coupling:
//            concurrent: x_at_exchange (3, x at the last exchange, whose pairs the window's end uses)
// fluid_solid: one row: exchanges (i64, number so far), pairs and cut_cells (i64, of the last exchange),
//            solid_volume (the solid volume inside the fluid mesh [m^3]), force (3, the total fluid force
//            on the solid [N]), penalty (3, its absorption part), penalty_scale (sum of |penalty| over pairs
//            and components: the round-off scale of the balance), absorption (3, the fluid's absorption force
//            summed over its tets: minus `penalty` to round-off), previous_force (3), previous_change (3) and
//            growing (i64, consecutive exchanges it grew): the watch for a growing oscillation of the force
//            (added-mass instability); concurrent only: older_change (3, the change two fluid steps back)
//            and fluid_ahead (u8, 1: the stored fluid state is already the window's end, a checkpoint having
//            joined its step)
#include <cstdint>

#include "engine/core/column_ref.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/solid_tables.hpp"

namespace rift::coupling {

inline constexpr const char* state_table = "fluid_solid";

// The coupling's columns of fluid_tet; solid_dilatation with fluid_solid.dilatation (the solid's rate of
// volume change per unit volume of K [1/s]), network_cell with fluid_solid.network_inlet (1: the cracks'
// network owns the cell's fluid).
namespace cell {
inline constexpr ColumnRef<double> solid_volume{fluid::tet_table, "solid_volume"};
inline constexpr ColumnRef<double> solid_fraction{fluid::tet_table, "solid_fraction"};
inline constexpr ColumnRef<double, 3> solid_velocity{fluid::tet_table, "solid_velocity"};
inline constexpr ColumnRef<double> absorption{fluid::tet_table, "absorption"};
inline constexpr ColumnRef<double> solid_dilatation{fluid::tet_table, "solid_dilatation"};
inline constexpr ColumnRef<double, 3> velocity_before{fluid::tet_table, "velocity_before"};
inline constexpr ColumnRef<double> network_cell{fluid::tet_table, "network_cell"};
}  // namespace cell

// The coupling's columns of the solid's tables.
namespace solid_node {
inline constexpr ColumnRef<double> fluid_added_mass{solid::node_table, "fluid_added_mass"};
inline constexpr ColumnRef<double, 3> window_velocity{solid::node_table, "window_velocity"};
inline constexpr ColumnRef<double, 3> x_at_exchange{solid::node_table, "x_at_exchange"};
}  // namespace solid_node
namespace solid_tet {
// the tet's volume at the last exchange, for the solid's dilatation rate
inline constexpr ColumnRef<double> volume_at_exchange{solid::tet_table, "volume_at_exchange"};
}  // namespace solid_tet

// fluid_solid: one row, created in this order.
namespace state {
inline constexpr ColumnRef<int64_t> exchanges{state_table, "exchanges"};
inline constexpr ColumnRef<int64_t> pairs{state_table, "pairs"};
inline constexpr ColumnRef<int64_t> cut_cells{state_table, "cut_cells"};
inline constexpr ColumnRef<double> solid_volume{state_table, "solid_volume"};
inline constexpr ColumnRef<double> penalty_scale{state_table, "penalty_scale"};
inline constexpr ColumnRef<double, 3> force{state_table, "force"};
inline constexpr ColumnRef<double, 3> penalty{state_table, "penalty"};
inline constexpr ColumnRef<double, 3> absorption{state_table, "absorption"};
inline constexpr ColumnRef<double, 3> previous_force{state_table, "previous_force"};
inline constexpr ColumnRef<double, 3> previous_change{state_table, "previous_change"};
inline constexpr ColumnRef<int64_t> growing{state_table, "growing"};
inline constexpr ColumnRef<double> inlet_injected{state_table, "inlet_injected"};
inline constexpr ColumnRef<double> inlet_sink_mass{state_table, "inlet_sink_mass"};
inline constexpr ColumnRef<uint8_t> fluid_ahead{state_table, "fluid_ahead"};
inline constexpr ColumnRef<double, 3> older_change{state_table, "older_change"};
}  // namespace state

}  // namespace rift::coupling
