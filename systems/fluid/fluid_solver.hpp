#pragma once
// Incompressible Navier-Stokes on a tet mesh: P1-P1 (equal order) with pressure-gradient-projection
// stabilisation, theta scheme in time, Picard linearisation (docs/fluid.md has the equations and the
// reasons). Per step n -> n+1, from u^0 = u^n, p^0 = p^n, for k = 0, 1, ... until the changes in u and p
// fall below picard_tol:
//   1. momentum (three scalar systems, one matrix, Jacobi-BiCGSTAB), advecting w = theta u^k + (1-theta) u^n:
//        rho (u* - u^n)/dt + theta L(w) u* + (1-theta) L(w) u^n + sigma (u* - u_s) + grad p^k = f + s
//   2. continuity residual R(u*, p^k) = div u* - div(tau_p (grad p - xi(p))), xi(p) = lumped projection
//      of grad p (linear in p, so implicit);
//   3. schur_gmres (default): S delta = -R by FGMRES, S v = R(A^-1(-G v), v) the pressure Schur complement,
//      preconditioned by [(c + tau_p) K]^-1 (BoomerAMG-PCG) + chi diag(M_L/mu + tau_p K)^-1, c = 1/(rho/dt
//      + sigma) (sigma in the pressure operator, fluid.md 1.3); u = u* + A^-1(-G delta), p = p^k + delta:
//      each Picard iteration solves the linearised monolithic stabilised theta step (no splitting error).
//      projection: one correction -div((c + tau_p) grad phi) = -R, u = u* - c grad phi (lumped),
//      p += phi; its fixed point is the same, reached more slowly when mu dt / (rho h^2) >> 1.
// Boundary conditions live on the mesh's named surfaces.
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/linear/csr_matrix.hpp"
#include "engine/linear/fgmres.hpp"
#include "engine/linear/hypre_pcg.hpp"
#include "engine/linear/krylov.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"
#include "kernels/fluid_subscale.hpp"
#include "systems/fluid/fluid_assembly.hpp"

namespace rift::fluid {

using Vec3 = std::array<double, 3>;
using VectorField = std::function<Vec3(const Vec3& x, double t)>;
using ScalarField = std::function<double(const Vec3& x, double t)>;

// The scene's enums, so that a scene's name maps to the solver's value in one place (the reader).
using BoundaryKind = FluidBoundarySpec::Kind;
using PressureCoupling = FluidSpec::Coupling;

struct FluidBoundary {
  std::string surface;
  BoundaryKind kind = BoundaryKind::no_slip;
  VectorField velocity;  // kind == velocity
  ScalarField pressure;  // kind == pressure
};

struct FluidSettings {
  double rho = 1.0;    // density [kg/m^3]
  double mu = 1.0;     // dynamic viscosity [Pa s]
  double dt = 1e-2;    // time step [s]
  double theta = 1.0;  // 1 backward Euler, 0.5 Crank-Nicolson
  bool convection = true;
  bool supg = true;                   // orthogonal-subscale stabilisation of the convection
  double pressure_stabilisation = 1;  // factor on tau_p (0 = none: unstable for P1-P1 at steady state)
  // The pressure subscale is dynamic (kernels/fluid_subscale.hpp): tau_t = 1 / (rho/dt + 1/tau_p) in the
  // step, and the subscale's memory carried from step to step; the steady state is that of tau_p. false:
  // quasi-static (tau_p in the step), whose Schur complement the preconditioner cannot reach when
  // tau_p >> dt / rho (a low-viscosity fluid at rest).
  bool dynamic_subscale = false;
  double viscous_correction = 1.0;             // chi above, in the Schur preconditioner
  double projection_viscous_correction = 0.0;  // chi as a Richardson step (projection): > 0.5 diverged
  int picard_max_iterations = 20;
  // First Picard iterate (advecting velocity and Krylov initial guess) extrapolated in time,
  // u^{n+1,0} = 2 u^n - u^{n-1} (not on the first step after construction or set_velocity): a
  // second-order guess, so fewer iterations reach picard_tol; the converged step does not depend on it.
  bool picard_extrapolate = true;
  double picard_tol = 1e-6;  // on max|du|/max|u| and max|dp|/max(max|p|, rho max|u|^2)
  double velocity_rel_tol = 1e-10;
  // Inexact Picard: forcing terms of the inner solves that the next Picard iteration (or time step)
  // corrects. The momentum predictor's BiCGSTAB stops once the residual of the current iterate is
  // reduced by velocity_forcing (or velocity_rel_tol is met); in projection mode the pressure
  // correction's PCG (initial guess 0) stops at max(pressure_solver.rel_tol, projection_forcing). The
  // errors are then a fraction of the update, and the fixed point (the steady state) is unchanged. The
  // Schur operator's inner solves always use velocity_rel_tol. 0 = off (every solve to full tolerance).
  // Measured on the Re = 100 cavity: velocity 0.1 and projection 1e-3 reach the same steady state;
  // projection 1e-2 stalled the march at a per-step change of ~2e-6 (16^2).
  double velocity_forcing = 0.0;
  double projection_forcing = 0.0;
  int velocity_max_iterations = 2000;
  PressureCoupling coupling = PressureCoupling::schur_gmres;
  double schur_rel_tol = 1e-8;  // FGMRES on the Schur complement, relative to its initial residual
  int schur_restart = 100;      // a restart discards the Krylov space (docs/fluid.md)
  int schur_max_iterations = 200;
  AmgPcgSettings pressure_solver{};
  bool verbose = false;  // one line per Picard iteration on stderr
};

struct FluidStepReport {
  int picard_iterations = 0;
  double velocity_change = 0.0, pressure_change = 0.0;  // relative, last Picard iteration
  bool converged = false;
  int velocity_iterations = 0;  // BiCGSTAB, summed over components and Picard iterations
  int pressure_iterations = 0;  // PCG, summed over Picard iterations
  int amg_setups = 0;
  int schur_iterations = 0;  // FGMRES, summed over Picard iterations (schur_gmres)
  // The last Picard iteration's linear solves met their tolerances (FGMRES on the Schur complement,
  // BiCGSTAB on momentum). A step is converged only if they did: a solve stopped at its iteration cap
  // makes a small Picard change that is not convergence.
  bool linear_converged = true;
  double schur_residual = 0.0, schur_target = 0.0;  // of the last Schur solve that missed its target
  int momentum_failures = 0;    // BiCGSTAB solves stopped at velocity_max_iterations, over the step
  double divergence_l2 = 0.0;   // sqrt(sum_t V_t (div u_t)^2) of u^{n+1}
  double divergence_max = 0.0;  // max_t |div u_t|
  double cfl = 0.0;             // max_t |u_t| dt / h_t, h_t = longest edge
};

// Where the solver's state lives: columns of the store (the fluid tables, FluidModel) in a run, or the
// solver's own for a solver used on its own. A step reads u^n, u^{n-1} and p^n, computes u^{n+1} and
// p^{n+1} into spare columns of its own, and updates the preconditioner's coefficients and the pressure
// subscale in place; commit() then swaps the spares with velocity and pressure (and velocity with
// previous_velocity): no value is copied between the solver and the store, and until the commit the
// columns hold the last committed step, whatever the step in flight is doing.
struct FluidStateColumns {
  Column* velocity = nullptr;                     // u^n, f64 x 3 per node
  Column* previous_velocity = nullptr;            // u^{n-1}, f64 x 3 per node (valid when has_previous)
  Column* pressure = nullptr;                     // p^n, f64 x 1 per node
  Column* pressure_matrix_coefficient = nullptr;  // f64 x 1 per tet (restored())
  Column* pressure_subscale = nullptr;            // f64 x 3 per tet (kernels/fluid_subscale.hpp)
  Column* has_previous = nullptr;                 // u8, row 0: 1 once a step was committed
};

class FluidSolver {
 public:
  FluidSolver(const TetMesh& mesh, FluidSettings settings, std::vector<FluidBoundary> boundaries);
  ~FluidSolver();
  FluidSolver(FluidSolver&&) noexcept;
  FluidSolver& operator=(FluidSolver&&) noexcept;  // a remeshed fluid (FluidModel::remesh)

  // Coupling inputs, one value per tet, zero by default: absorption sigma [kg/(m^3 s)] (implicit, relaxes
  // u towards target), target velocity u_s (3 per tet), and the divergence the continuity equation
  // allows, div u = s [1/s] (the immersed solid's rate of volume change per unit volume). The solver
  // reads them in place where the coupling keeps them (the store's fluid_tet columns, systems/coupling),
  // never copied: the spans must hold nt, 3 nt and nt values (an empty dilatation keeps the zeros) and
  // stay valid and unchanged while a step runs. Call absorption_changed() after their values change (the
  // pressure operator depends on sigma).
  void read_coupling_inputs(std::span<const double> sigma, std::span<const double> target,
                            std::span<const double> dilatation);
  std::span<const double> absorption() const { return sigma_; }  // the sigma the solver reads
  // The solver's own input arrays (zeros at construction), for a solver used on its own (tests, studies):
  // each call points the solver back at that array, which the caller then fills.
  std::span<double> own_sigma() {
    sigma_ = own_sigma_;
    return own_sigma_;
  }
  std::span<double> own_target_velocity() {
    target_ = own_target_;
    return own_target_;
  }
  // Momentum source s [N/m^3] (3 per tet), zero by default.
  std::span<double> source() { return source_; }
  // The weight of the continuity equation per tet, w in [0, 1] (1 by default). Where w < 1 the equation
  // is w div u = w s, and the divergence of (1 - w) c (f - grad p) (c = 1 / (rho/dt + sigma): the flux of
  // the fluid relative to the target) takes the rest of the row. With w = 1 - alpha (alpha: the fraction
  // of a cell an immersed solid fills) continuity holds where the fluid is, and inside the solid the
  // pressure is the extension of the fluid's that lets no fluid through the solid, instead of the answer
  // to the solid's volume changes (docs/coupling.md). Call absorption_changed() after writing it.
  std::span<double> continuity_weight() { return continuity_weight_; }
  // A volume source per tet, div u = q [1/s], not weighted by the continuity's weight (a sink where fluid
  // leaves the mesh into the cracks' network: its integral is what leaves, exactly).
  std::span<double> volume_source() { return volume_source_; }
  void absorption_changed() { pressure_matrix_stale_ = true; }
  // Body force per unit volume f(x, t) [N/m^3], evaluated at the nodes (theta-weighted in time).
  void set_body_force(VectorField f) { body_force_fn_ = std::move(f); }

  // The state's columns from now on (sizes checked against the mesh); the solver's own until then.
  void use_state(const FluidStateColumns& columns);
  void set_velocity(const VectorField& u0);  // at the current time; also sets u on Dirichlet nodes
  // A uniform pressure p^n (the first Picard iterate).
  void set_pressure(double p0);
  void set_time(double t) { time_ = t; }

  // One time step: advance() computes it, commit() makes it the state. Between the two the state's
  // columns still hold the last committed step (what a run's outputs read while the concurrent coupling's
  // step is in flight); every advance() must be committed before the next. step() does both.
  FluidStepReport advance();
  void commit();
  FluidStepReport step() {
    FluidStepReport r = advance();
    commit();
    return r;
  }

  // The state's columns were written from outside (a checkpoint read back, a remesh's interpolation): take
  // them up at time t. Besides u and p a step depends on the coefficients the pressure matrix (the
  // preconditioner, rebuilt only when they drift) was last assembled with, one per tet (all zero: not
  // assembled yet), on u^{n-1} (picard_extrapolate, when has_previous) and on the pressure subscale
  // (dynamic_subscale): with the values a run held at t, the next step is bitwise the one it took.
  void restored(double t);
  std::span<const double> pressure_matrix_coefficients() const {
    return state(columns_.pressure_matrix_coefficient);
  }
  std::span<const double> pressure_subscale() const { return state(columns_.pressure_subscale); }
  std::span<const double> previous_velocity() const { return state(columns_.previous_velocity); }
  bool has_previous() const { return columns_.has_previous->values<uint8_t>()[0] != 0; }

  double time() const { return time_; }
  std::span<const double> velocity() const { return state(columns_.velocity); }  // 3 per node
  std::span<const double> pressure() const { return state(columns_.pressure); }  // 1 per node
  std::span<const double> nodes() const { return x_; }                           // 3 per node
  std::span<const int32_t> tets() const { return tet_nodes_; }
  std::span<const double> volumes() const { return volume_; }
  // The P1 shape-function gradients (12 per tet) and longest edges (1 per tet) of the mesh
  // (kernels::p1_prepare), fixed until the mesh changes.
  std::span<const double> gradients() const { return grad_; }
  std::span<const double> element_sizes() const { return h_; }
  std::span<const double> node_volumes() const { return node_volume_; }  // lumped: a quarter of each tet
  const FluidSettings& settings() const { return settings_; }
  size_t node_count() const { return x_.size() / 3; }

 private:
  struct SchurStats {
    int iterations = 0, velocity_iterations = 0, pressure_iterations = 0;
    double residual = 0.0, target = 0.0;
    bool converged = false;
  };
  void build_component_matrices();
  int solve_momentum(std::span<const double> rhs3, std::span<double> u3, bool homogeneous,
                     double forcing = 0.0);
  kernels::PressureSubscaleArgs subscale_args() const;
  void add_dilatation(std::span<double> residual) const;
  void schur_velocity(std::span<const double> v, std::span<double> u_v, int& velocity_iterations);
  void schur_apply(std::span<const double> v, std::span<double> sv, SchurStats& st);
  void schur_precondition(std::span<const double> r, std::span<double> z, SchurStats& st);
  SchurStats schur_solve(std::span<const double> b, std::span<double> delta);
  void apply_velocity_bc(double t);
  void assemble_pressure_matrix();
  void project_convective_derivative();  // eta_ from w_ (kernels/fluid_convection_subscale.hpp)
  // For the Picard test and the Schur floor, of a velocity and pressure.
  double velocity_scale(std::span<const double> u, std::span<const double> p) const;
  static std::span<double> state(Column* c) { return c->values<double>(); }
  // The continuity's weights for the element loops: empty while every weight is 1 (the plain equation).
  std::span<const double> continuity_weights() const {
    return weighted_ ? std::span<const double>(continuity_weight_) : std::span<const double>{};
  }
  std::span<const double> relative_flux() const {
    return weighted_ ? std::span<const double>(relative_flux_) : std::span<const double>{};
  }
  void update_cell_coefficients();

  FluidSettings settings_;
  std::vector<FluidBoundary> boundaries_;
  double time_ = 0.0;
  std::vector<double> x_, volume_, grad_, h_;
  std::vector<int32_t> tet_nodes_;
  std::vector<double> node_volume_;  // lumped mass sum_t V/4
  std::vector<double> visc_diag_;    // diagonal of M_L / mu + sum tau_p K
  // Boundary conditions: per node and component, the boundary fixing it (-1 free; free slip fixes the
  // normal component to 0, recorded as -2).
  std::vector<int32_t> vel_fixed_by_;
  std::vector<double> vel_value_;  // 3 per node at the time of the last apply_velocity_bc
  std::vector<int32_t> pressure_fixed_by_;
  std::vector<uint8_t> phi_fixed_;
  std::vector<double> phi_value_;
  // State: the columns it lives in, the solver's own (until use_state, or for a solver on its own: on the
  // heap, so that a moved solver's pointers stay valid), and the spares a step computes u^{n+1} and
  // p^{n+1} into (commit swaps them in).
  struct OwnState;
  std::unique_ptr<OwnState> own_state_;
  FluidStateColumns columns_;
  Column next_velocity_{"fluid_solver", "next_velocity", ElementType::f64, 3};
  Column next_pressure_{"fluid_solver", "next_pressure", ElementType::f64, 1};
  // Fields of a step: u_ and p_ the iterates (the spares' values), u_old_ the step's u^n.
  std::span<double> u_, p_;
  std::span<const double> u_old_;
  std::vector<double> u_star_, u_iter_, p_iter_, xi_, w_, body_force_;
  std::vector<double> eta_;  // projected convective derivative of w (3 per node)
  std::vector<double> own_sigma_, own_target_, own_dilatation_;  // zeros until a caller fills them
  std::span<const double> sigma_, target_, dilatation_;          // read_coupling_inputs
  std::vector<double> source_, continuity_weight_, volume_source_;
  std::vector<double> supg_tau_, tau_p_, c_cell_, pcoef_, div_;
  std::vector<double> subscale_rhs_;   // the pressure subscale's explicit continuity term
  int momentum_failures_ = 0;          // BiCGSTAB solves that missed their tolerance
  bool weighted_ = false;              // some continuity weight is below 1
  std::vector<double> relative_flux_;  // (1 - w) c per tet, while weighted_
  // Linear algebra.
  CsrMatrix momentum_, pressure_mat_;
  std::array<CsrMatrix, 3> comp_;         // momentum with the Dirichlet rows of each component
  std::array<bool, 3> comp_all_fixed_{};  // every node's component fixed (e.g. w in a free-slip slab)
  Fgmres fgmres_;                         // the Schur complement's solver and its workspace
  std::vector<double> u_v_, xi_v_, grad_v_, prec_rhs_;
  std::vector<int32_t> slot_, diag_slot_;
  FluidAssembly assembly_;  // the parallel element loops (momentum, pressure matrix, rhs, gradients)
  std::vector<double> rhs_, rhs_c_, x_c_, prhs_, cont_res_, phi_, corr_;
  BicgstabJacobi bicgstab_;
  std::unique_ptr<HypreAmgPcg> amg_;
  bool pressure_matrix_stale_ = true;
  bool closed_ = false;  // no pressure boundary
  double schur_reference_ = 0.0;
  // Round-off floor of the Schur residual: 1e-12 x (velocity scale) x sqrt(sum_n V_n^(4/3)), the continuity
  // residual of a relative 1e-12 velocity perturbation. A fluid at rest starts at round-off, where a
  // relative reduction cannot be had.
  double schur_floor_ = 0.0, residual_area_ = 0.0;
  VectorField body_force_fn_;
};

}  // namespace rift::fluid
