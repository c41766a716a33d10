#pragma once
// Names of the fluid's tables and columns (systems/fluid/fluid_model.hpp), so the system declares access
// with the same strings the store uses.
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

// fluid_step's columns by type (the fluid step writes them all).
inline constexpr const char* step_counts[] = {"picard_iterations", "velocity_iterations",
                                              "schur_iterations",  "pressure_iterations",
                                              "amg_setups",        "picard_failures"};
inline constexpr const char* step_flags[] = {"converged", "has_previous"};
inline constexpr const char* step_measures[] = {
    "velocity_change", "pressure_change", "divergence_l2", "divergence_max", "cfl",
    "max_cfl",         "max_divergence"};

inline std::string col(const char* table, const char* column) {
  return std::string(table) + "." + column;
}

}  // namespace rift::fluid
