#pragma once
// One implicit (backward Euler) step of lubrication flow on a crack network: P1 control volumes on the
// crack's mid-surface triangles (kernels/fracture_flow.hpp), a slightly compressible fluid, a fluid lag
// ahead of the front, fixed-pressure vertices (a well under pressure control, a vent) and mass sources.
//
// Vertex roles:
//   wet      the vertex's control volume is full: its pressure is an unknown of the step;
//   filling  fluid has reached it but not filled it: it holds the lag pressure and takes in fluid;
//   dry      no fluid: it holds the lag pressure; it starts filling once a wet neighbour pushes fluid in;
//   fixed    its pressure is given (a reservoir): what flows in or out is booked as vented / supplied.
// The step is mass conservative by construction: each edge's mass flux leaves one vertex and enters the
// other (fluid never flows out of a vertex that is not wet). The linear solve uses rho V linearised about
// the old pressure (storage S = rho0 V / K_f + rho C, symmetric positive definite with the Laplacian);
// the new masses then give each wet vertex's pressure through the equation of state exactly.
//
// The volume a vertex offers may depend on its pressure within the step: V(p) = V_pred + C (p - p_applied),
// where C is the compliance of the walls over the step (the solid's nodes move under the pressure change;
// systems/fracture_flow/fracture_flow_system.cpp). Closing that loop inside the step keeps the fluid's
// stiffness K_f / w from entering the explicit solid's stable step.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"
#include "kernels/fracture_flow.hpp"

namespace rift {

enum class FlowRole : uint8_t { dry = 0, filling = 1, wet = 2, fixed = 3 };

struct NetworkFlowStepInput {
  double dt = 0.0;
  double time = 0.0;                       // at the end of the step (wetting times)
  std::span<const double> triangle_x;      // 9 per triangle: mid-surface corners
  std::span<const double> aperture;        // 3 per triangle: hydraulic aperture at the corners (floored)
  std::span<const double> volume;          // 1 per vertex: V_pred [m^3]
  std::span<const double> compliance;      // 1 per vertex: C [m^3/Pa], >= 0
  std::span<const double> applied;         // 1 per vertex: p_applied, the pressure V_pred already felt
  std::span<const double> source;          // 1 per vertex: mass rate in [kg/s]
  std::span<const double> fixed_pressure;  // 1 per vertex: the pressure of a fixed vertex
  // 1 per vertex, or empty: the compliance of the vertex's open corners only, and the volume its corners
  // hold at the aperture floor. A wet vertex whose volume V_pred + C (p - p_applied) would fall below the
  // floor volume is closing: its floored corners' volume does not follow their nodes, so it takes the open
  // compliance instead and the step is solved again (an active set, like the cavitation's). If even so it
  // would fall below its floor (walls far more compliant than the fluid, drained fast), its walls close
  // onto the floor within the step and no further: its volume is the floor volume, whatever its pressure.
  std::span<const double> compliance_open = {};
  std::span<const double> floor_volume = {};
};

struct NetworkFlowState {
  std::span<double> pressure;      // 1 per vertex [Pa]
  std::span<double> mass;          // 1 per vertex [kg]
  std::span<uint8_t> role;         // 1 per vertex (FlowRole)
  std::span<double> wetting_time;  // 1 per vertex [s], -1 until fluid first reaches the vertex
  std::span<double> exchanged;     // 1 per vertex, added to: mass a fixed vertex gave the network [kg]
};

// Running totals. Mass: the change of the network's mass (sum of every vertex's, fixed ones included)
// equals sourced + the fixed vertices' exchanged, to rounding.
struct NetworkFlowBooks {
  double sourced = 0.0;      // mass the sources put in [kg]
  double dissipation = 0.0;  // viscous dissipation [J]: sum over steps and edges of dt T_e (p_i - p_j)^2
};

// How the pressure system is solved: a sparse LDLT factorisation (exact; its fill-in grows faster than
// the network: 2.8 ms a step at 1e4 triangles), or conjugate gradients with a diagonal preconditioner
// started from the last pressure, which changes little from one step to the next (15-20 iterations to a
// relative residual of 1e-10; 0.7 ms at 1e4 triangles; an incomplete Cholesky preconditioner cost more to
// build each step than it saved); `automatic` takes the factorisation below kDirectVertices vertices and CG
// above. Mass is conserved either way (the fluxes of the solution are applied to both ends of each edge).
using NetworkSolver = FractureFlowSpec::Solver;  // the scene's enum: its names map in the reader

class NetworkFlow {
 public:
  static constexpr size_t kDirectVertices = 2000;
  NetworkFlow(kernels::FluidEos eos, double viscosity, double lag_pressure,
              NetworkSolver solver = NetworkSolver::automatic);

  // The network: triangles on vertex ids [0, vertex_count), two corners of a triangle possibly on one
  // vertex (a lumped well). Builds the edges and the matrix pattern; call again whenever triangles are
  // added.
  void set_network(std::span<const int32_t> triangles, size_t vertex_count);

  // A step in which no fluid moves between vertices: each keeps its mass (plus what the caller added) and
  // takes the pressure of its own volume; fixed vertices refill. Between flow solves (`interval`).
  std::string local_step(const NetworkFlowStepInput& in, NetworkFlowState& s);

  // One step: updates state, adds to books. Returns "" or what went wrong (a failed factorisation, a
  // non-finite pressure, fluid drawn from an empty vertex); the caller then stops the run with that
  // diagnosis, since the state is part-way through the step.
  std::string step(const NetworkFlowStepInput& in, NetworkFlowState& s, NetworkFlowBooks& books);

  size_t edge_count() const { return edge_v_.size() / 2; }
  size_t negative_transmissibilities() const { return negative_; }  // edges opposite obtuse angles, last step
  int cg_iterations() const { return cg_iterations_; }  // of the last solve (0 for the factorisation)
  // After a step, per vertex: the volume the step gave it at its new pressure (the fluid's volume), and
  // the pressure its walls take within the step: its new pressure, except for a vertex closed onto its
  // floor, whose walls move only as far as the floor (the pressure change that brings its open corners
  // there: p_applied + (V_floor - V_pred) / C_open), the rest being carried by the rock.
  std::span<const double> volume_used() const { return volume_used_; }
  std::span<const double> wall_pressure() const { return wall_pressure_; }

 private:
  void transmissibilities(const NetworkFlowStepInput& in);
  double edge_transmissibility(size_t e, const NetworkFlowState& s) const;
  void edge_densities(const NetworkFlowState& s);
  std::string solve_pressures(const NetworkFlowStepInput& in, const NetworkFlowState& s);
  std::string zero_viscosity_step(const NetworkFlowStepInput& in, NetworkFlowState& s, NetworkFlowBooks& b);
  // After the masses moved: fixed vertices refill to their pressure (booked as exchanged), wet ones take
  // the pressure of their mass, filling ones turn wet once full, and a wet one whose pressure would fall
  // below the lag pressure cavitates back to filling.
  // from_solve: wet vertices keep the solve's pressure (else they take the pressure of their mass).
  std::string update_roles(const NetworkFlowStepInput& in, NetworkFlowState& s, bool from_solve);
  // How far a vertex's walls may close within the step (NetworkFlowStepInput::floor_volume).
  enum class Closing : uint8_t { open = 0, open_corners = 1, closed = 2 };
  static constexpr size_t kFreePasses = 8;
  static double stage_compliance(const NetworkFlowStepInput& in, size_t v, Closing stage);
  bool stage_holds(const NetworkFlowStepInput& in, const NetworkFlowState& s, size_t v, double p,
                   Closing stage) const;
  Closing stage_at(const NetworkFlowStepInput& in, const NetworkFlowState& s, size_t v, double p) const;
  // A fixed vertex refills to its pressure: its volume there must not fall below its floor either.
  void close_fixed(const NetworkFlowStepInput& in, const NetworkFlowState& s);
  void start_step();
  void finish_step(const NetworkFlowStepInput& in, const NetworkFlowState& s);

  kernels::FluidEos eos_;
  double viscosity_, lag_pressure_;
  size_t vertices_ = 0;
  std::vector<int32_t> triangles_;
  std::vector<int32_t> edge_v_;         // 2 per edge, i < j, sorted
  std::vector<int32_t> triangle_edge_;  // 3 per triangle: the edge opposite each corner (-1: none)
  std::vector<double> transmissibility_, edge_density_, vertex_density_;
  std::vector<double> new_pressure_;
  std::vector<int32_t> component_;
  std::vector<double> part_mass_, part_v0_, part_compliance_;  // zero-viscosity mode, per component
  std::vector<int64_t> part_fixed_;
  std::vector<uint8_t> stage_;  // per vertex, this step: Closing
  std::vector<double> volume_used_, wall_pressure_;
  double compliance_at(const NetworkFlowStepInput& in, size_t v) const {
    return stage_compliance(in, v, Closing(stage_[v]));
  }
  double volume_at(const NetworkFlowStepInput& in, size_t v, double p) const {
    return Closing(stage_[v]) == Closing::closed ? in.floor_volume[v]
                                                 : in.volume[v] + compliance_at(in, v) * (p - in.applied[v]);
  }
  std::vector<int32_t> diagonal_slot_, edge_slot_;  // positions in the matrix's value array
  Eigen::SparseMatrix<double> matrix_;
  NetworkSolver solver_kind_;
  bool use_cg_ = false;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::DiagonalPreconditioner<double>>
      cg_;
  int cg_iterations_ = 0;
  Eigen::VectorXd rhs_, solution_;
  size_t negative_ = 0;
};

}  // namespace rift
