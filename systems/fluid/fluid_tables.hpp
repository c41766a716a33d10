#pragma once
// The fluid's tables and their columns (systems/fluid/fluid_model.hpp), each column declared once as a
// ColumnRef (engine/core/column_ref.hpp), in the order they are created.
//
// fluid_node: x (3, position, fixed), velocity (3), pressure (1): the state after the last step;
//            previous_velocity (3): the velocity before it (the next step's extrapolated start)
// fluid_tet: nodes (i32 x4), pressure_matrix_coefficient (1): what the pressure preconditioner was last
//            assembled with (part of the state a step depends on; see FluidSolver::restored);
//            pressure_subscale (3): the dynamic pressure subscale u' (kernels/fluid_subscale.hpp), state
// fluid_step: one row, the last step's report: the counts (i64) picard_iterations, velocity_iterations,
//            schur_iterations, pressure_iterations, amg_setups; converged (u8, 1/0); the measures (f64)
//            velocity_change, pressure_change, divergence_l2, divergence_max, cfl. Running figures over the
//            run: picard_failures (i64), max_cfl, max_divergence (f64); has_previous (u8, 1/0:
//            previous_velocity is valid); with fluid.adapt, remeshes (i64: the mesh's revision, how many
//            times it was remade)
// fluid_boundary (fluid.adapt only): nodes (i32 x3), surface (i32, index into the mesh's surface names):
//            the boundary triangles, so a restart rebuilds the solver on the mesh the store holds
#include <cstdint>
#include <string>

#include "engine/core/column_ref.hpp"

namespace rift::fluid {

inline constexpr const char* node_table = "fluid_node";
inline constexpr const char* tet_table = "fluid_tet";
inline constexpr const char* step_table = "fluid_step";
inline constexpr const char* boundary_table = "fluid_boundary";

// The fluid's own columns of fluid_node and fluid_tet (the coupling's are in
// systems/coupling/fluid_solid_tables.hpp).
namespace node {
inline constexpr ColumnRef<double, 3> x{node_table, "x"};
inline constexpr ColumnRef<double, 3> velocity{node_table, "velocity"};
inline constexpr ColumnRef<double> pressure{node_table, "pressure"};
inline constexpr ColumnRef<double, 3> previous_velocity{node_table, "previous_velocity"};
}  // namespace node
namespace tet {
inline constexpr ColumnRef<int32_t, 4> nodes{tet_table, "nodes"};
inline constexpr ColumnRef<double> pressure_matrix_coefficient{tet_table, "pressure_matrix_coefficient"};
inline constexpr ColumnRef<double, 3> pressure_subscale{tet_table, "pressure_subscale"};
}  // namespace tet

namespace boundary {
inline constexpr ColumnRef<int32_t, 3> nodes{boundary_table, "nodes"};
inline constexpr ColumnRef<int32_t> surface{boundary_table, "surface"};
}  // namespace boundary

// fluid_step's columns, by type in the order they are created (the fluid step writes them all).
namespace step {
inline constexpr ColumnRef<int64_t> picard_iterations{step_table, "picard_iterations"};
inline constexpr ColumnRef<int64_t> velocity_iterations{step_table, "velocity_iterations"};
inline constexpr ColumnRef<int64_t> schur_iterations{step_table, "schur_iterations"};
inline constexpr ColumnRef<int64_t> pressure_iterations{step_table, "pressure_iterations"};
inline constexpr ColumnRef<int64_t> amg_setups{step_table, "amg_setups"};
inline constexpr ColumnRef<int64_t> picard_failures{step_table, "picard_failures"};
inline constexpr ColumnRef<uint8_t> converged{step_table, "converged"};
inline constexpr ColumnRef<uint8_t> has_previous{step_table, "has_previous"};
inline constexpr ColumnRef<double> velocity_change{step_table, "velocity_change"};
inline constexpr ColumnRef<double> pressure_change{step_table, "pressure_change"};
inline constexpr ColumnRef<double> divergence_l2{step_table, "divergence_l2"};
inline constexpr ColumnRef<double> divergence_max{step_table, "divergence_max"};
inline constexpr ColumnRef<double> cfl{step_table, "cfl"};
inline constexpr ColumnRef<double> max_cfl{step_table, "max_cfl"};
inline constexpr ColumnRef<double> max_divergence{step_table, "max_divergence"};
inline constexpr ColumnRef<int64_t> remeshes{step_table, "remeshes"};  // with fluid.adapt only

inline constexpr ColumnRef<int64_t> counts[] = {picard_iterations,   velocity_iterations, schur_iterations,
                                                pressure_iterations, amg_setups,          picard_failures};
inline constexpr ColumnRef<uint8_t> flags[] = {converged, has_previous};
inline constexpr ColumnRef<double> measures[] = {
    velocity_change, pressure_change, divergence_l2, divergence_max, cfl, max_cfl, max_divergence};
}  // namespace step

}  // namespace rift::fluid
