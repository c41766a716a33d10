#include "systems/fluid/fluid_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "kernels/fluid_convection_subscale.hpp"
#include "kernels/fluid_element.hpp"

namespace rift::fluid {

namespace {

double max_abs(std::span<const double> v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

// The state of a solver used on its own (no store): the same columns a run's fluid tables hold.
struct FluidSolver::OwnState {
  Column velocity{"fluid_solver", "velocity", ElementType::f64, 3};
  Column previous_velocity{"fluid_solver", "previous_velocity", ElementType::f64, 3};
  Column pressure{"fluid_solver", "pressure", ElementType::f64, 1};
  Column pressure_matrix_coefficient{"fluid_solver", "pressure_matrix_coefficient", ElementType::f64, 1};
  Column pressure_subscale{"fluid_solver", "pressure_subscale", ElementType::f64, 3};
  Column has_previous{"fluid_solver", "has_previous", ElementType::u8, 1};
  OwnState(size_t nodes, size_t tets) {
    for (Column* c : {&velocity, &previous_velocity, &pressure}) c->resize(nodes);
    for (Column* c : {&pressure_matrix_coefficient, &pressure_subscale}) c->resize(tets);
    has_previous.resize(1);
  }
  FluidStateColumns columns() {
    return {&velocity,          &previous_velocity, &pressure, &pressure_matrix_coefficient,
            &pressure_subscale, &has_previous};
  }
};

FluidSolver::FluidSolver(const TetMesh& mesh, FluidSettings settings, std::vector<FluidBoundary> boundaries)
    : settings_(settings), boundaries_(std::move(boundaries)) {
  if (!(settings_.dt > 0.0) || settings_.theta < 0.5 || settings_.theta > 1.0 || !(settings_.rho > 0.0) ||
      settings_.mu < 0.0)
    throw std::invalid_argument("FluidSolver: need dt > 0, 0.5 <= theta <= 1, rho > 0, mu >= 0");
  const size_t nn = mesh.nodes.size(), nt = mesh.tets.size();
  x_.reserve(3 * nn);
  for (const auto& p : mesh.nodes) x_.insert(x_.end(), p.begin(), p.end());
  tet_nodes_.reserve(4 * nt);
  for (const auto& t : mesh.tets) tet_nodes_.insert(tet_nodes_.end(), t.begin(), t.end());
  volume_.assign(nt, 0.0);
  grad_.assign(12 * nt, 0.0);
  h_.assign(nt, 0.0);
  if (kernels::p1_prepare(x_, tet_nodes_, volume_, grad_, h_) != 0)
    throw std::invalid_argument("FluidSolver: the mesh has inverted or degenerate tets");
  node_volume_.assign(nn, 0.0);
  for (size_t t = 0; t < nt; ++t)
    for (int a = 0; a < 4; ++a) node_volume_[tet_nodes_[4 * t + a]] += 0.25 * volume_[t];
  for (double v : node_volume_) {
    const double c = std::cbrt(v);
    residual_area_ += c * c * c * c;  // V^(4/3)
  }
  residual_area_ = std::sqrt(residual_area_);

  // Boundary conditions, in list order (a later Dirichlet boundary overrides an earlier one on shared
  // nodes; free slip never overrides a full Dirichlet condition).
  vel_fixed_by_.assign(3 * nn, -1);
  pressure_fixed_by_.assign(nn, -1);
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    const FluidBoundary& bc = boundaries_[b];
    const int32_t s = mesh.surface_index(bc.surface);
    if (s < 0) throw std::invalid_argument("FluidSolver: no surface named '" + bc.surface + "'");
    if (bc.kind == BoundaryKind::velocity && !bc.velocity)
      throw std::invalid_argument("FluidSolver: velocity boundary '" + bc.surface + "' has no function");
    if (bc.kind == BoundaryKind::pressure && !bc.pressure)
      throw std::invalid_argument("FluidSolver: pressure boundary '" + bc.surface + "' has no function");
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      if (mesh.triangle_surface[f] != s) continue;
      const auto& tri = mesh.triangles[f];
      int normal_axis = -1;
      if (bc.kind == BoundaryKind::free_slip) {
        double e1[3], e2[3], n[3];
        for (int d = 0; d < 3; ++d) {
          e1[d] = mesh.nodes[tri[1]][d] - mesh.nodes[tri[0]][d];
          e2[d] = mesh.nodes[tri[2]][d] - mesh.nodes[tri[0]][d];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int d = 0; d < 3; ++d)
          if (std::abs(n[d]) > (1.0 - 1e-9) * len) normal_axis = d;
        if (normal_axis < 0)
          throw std::invalid_argument("FluidSolver: free slip needs an axis-aligned plane; '" + bc.surface +
                                      "' is not");
      }
      for (int32_t node : tri) {
        switch (bc.kind) {
          case BoundaryKind::no_slip:
          case BoundaryKind::velocity:
            for (int d = 0; d < 3; ++d) vel_fixed_by_[3 * node + d] = static_cast<int32_t>(b);
            break;
          case BoundaryKind::free_slip: {
            bool full = true;
            for (int d = 0; d < 3; ++d) full = full && vel_fixed_by_[3 * node + d] >= 0;
            if (!full) vel_fixed_by_[3 * node + normal_axis] = -2;
            break;
          }
          case BoundaryKind::pressure:
          case BoundaryKind::outflow:
            pressure_fixed_by_[node] = static_cast<int32_t>(b);
            break;
        }
      }
    }
  }
  phi_fixed_.assign(nn, 0);
  phi_value_.assign(nn, 0.0);
  bool any_pressure = false;
  for (size_t n = 0; n < nn; ++n)
    if (pressure_fixed_by_[n] >= 0) {
      phi_fixed_[n] = 1;
      any_pressure = true;
    }
  // Closed domain: p is defined up to a constant. The Schur solve works on the singular consistent system
  // (right-hand side made zero-sum, p normalised to zero mean); the AMG preconditioner and the projection
  // scheme pin node 0 instead.
  closed_ = !any_pressure;
  if (closed_) phi_fixed_[0] = 1;

  own_state_ = std::make_unique<OwnState>(nn, nt);
  columns_ = own_state_->columns();
  next_velocity_.resize(nn);
  next_pressure_.resize(nn);
  for (auto* v : {&u_star_, &u_iter_, &xi_, &w_, &eta_, &body_force_, &vel_value_, &rhs_})
    v->assign(3 * nn, 0.0);
  for (auto* v : {&visc_diag_, &p_iter_, &rhs_c_, &x_c_, &prhs_, &cont_res_, &phi_}) v->assign(nn, 0.0);
  corr_.assign(3 * nn, 0.0);
  own_sigma_.assign(nt, 0.0);
  own_target_.assign(3 * nt, 0.0);
  own_dilatation_.assign(nt, 0.0);
  sigma_ = own_sigma_, target_ = own_target_, dilatation_ = own_dilatation_;
  source_.assign(3 * nt, 0.0);
  continuity_weight_.assign(nt, 1.0);
  volume_source_.assign(nt, 0.0);
  for (auto* v : {&supg_tau_, &tau_p_, &c_cell_, &pcoef_, &div_}) v->assign(nt, 0.0);
  subscale_rhs_.assign(nn, 0.0);

  momentum_ = p1_pattern(static_cast<int32_t>(nn), tet_nodes_);
  pressure_mat_ = momentum_;
  slot_ = p1_tet_slots(momentum_, tet_nodes_);
  diag_slot_ = diagonal_slots(momentum_);
  assembly_ = FluidAssembly(tet_nodes_, nn);
  bicgstab_.resize(static_cast<int32_t>(nn));
  for (auto& c : comp_) c = momentum_;
  for (int d = 0; d < 3; ++d) {
    comp_all_fixed_[d] = true;
    for (size_t n = 0; n < nn && comp_all_fixed_[d]; ++n) comp_all_fixed_[d] = vel_fixed_by_[3 * n + d] != -1;
  }
  const int m = std::max(settings_.schur_restart, 1);
  settings_.schur_restart = m;
  fgmres_.resize(nn, m);
  u_v_.assign(3 * nn, 0.0);
  xi_v_.assign(3 * nn, 0.0);
  grad_v_.assign(3 * nn, 0.0);
  prec_rhs_.assign(nn, 0.0);
  amg_ = std::make_unique<HypreAmgPcg>(settings_.pressure_solver);
  apply_velocity_bc(time_);
}

FluidSolver::~FluidSolver() = default;
// The input spans move with the vectors they view and the spares' buffers with their columns (a move keeps
// the buffer), and the state's columns with the heap object that holds them.
FluidSolver::FluidSolver(FluidSolver&&) noexcept = default;
FluidSolver& FluidSolver::operator=(FluidSolver&&) noexcept = default;

void FluidSolver::read_coupling_inputs(std::span<const double> sigma, std::span<const double> target,
                                       std::span<const double> dilatation) {
  const size_t nt = volume_.size();
  if (sigma.size() != nt || target.size() != 3 * nt || (!dilatation.empty() && dilatation.size() != nt))
    throw std::logic_error("FluidSolver::read_coupling_inputs: " + std::to_string(sigma.size()) + ", " +
                           std::to_string(target.size()) + " and " + std::to_string(dilatation.size()) +
                           " values for " + std::to_string(nt) + " tets");
  sigma_ = sigma;
  target_ = target;
  dilatation_ = dilatation.empty() ? std::span<const double>(own_dilatation_) : dilatation;
}

void FluidSolver::use_state(const FluidStateColumns& c) {
  const size_t nn = node_count(), nt = volume_.size();
  const auto fits = [](const Column* col, ElementType type, int width, size_t rows) {
    return col != nullptr && col->type() == type && col->components() == width && col->rows() == rows;
  };
  if (!fits(c.velocity, ElementType::f64, 3, nn) || !fits(c.previous_velocity, ElementType::f64, 3, nn) ||
      !fits(c.pressure, ElementType::f64, 1, nn) ||
      !fits(c.pressure_matrix_coefficient, ElementType::f64, 1, nt) ||
      !fits(c.pressure_subscale, ElementType::f64, 3, nt) || c.has_previous == nullptr ||
      c.has_previous->type() != ElementType::u8 || c.has_previous->rows() < 1)
    throw std::logic_error("FluidSolver::use_state: the state's columns do not fit the mesh (" +
                           std::to_string(nn) + " nodes, " + std::to_string(nt) + " tets)");
  columns_ = c;
}

void FluidSolver::set_velocity(const VectorField& u0) {
  const size_t nn = node_count();
  const std::span<double> u = state(columns_.velocity);
  for (size_t n = 0; n < nn; ++n) {
    const Vec3 v = u0({x_[3 * n], x_[3 * n + 1], x_[3 * n + 2]}, time_);
    for (int d = 0; d < 3; ++d) u[3 * n + d] = v[d];
  }
  apply_velocity_bc(time_);
  for (size_t i = 0; i < u.size(); ++i)
    if (vel_fixed_by_[i] != -1) u[i] = vel_value_[i];
  columns_.has_previous->values<uint8_t>()[0] = 0;
}

void FluidSolver::set_pressure(double p0) {
  const std::span<double> p = state(columns_.pressure);
  std::fill(p.begin(), p.end(), p0);
}

void FluidSolver::apply_velocity_bc(double t) {
  const size_t nn = node_count();
  for (size_t n = 0; n < nn; ++n) {
    const Vec3 xn{x_[3 * n], x_[3 * n + 1], x_[3 * n + 2]};
    for (int d = 0; d < 3; ++d) {
      const int32_t b = vel_fixed_by_[3 * n + d];
      double v = 0.0;
      if (b >= 0 && boundaries_[b].kind == BoundaryKind::velocity) {
        if (d == 0 || vel_fixed_by_[3 * n + d - 1] != b) {
          const Vec3 g = boundaries_[b].velocity(xn, t);
          for (int e = d; e < 3; ++e)
            if (vel_fixed_by_[3 * n + e] == b) vel_value_[3 * n + e] = g[e];
        }
        continue;
      }
      vel_value_[3 * n + d] = v;
    }
    const int32_t pb = pressure_fixed_by_[n];
    phi_value_[n] = 0.0;
    if (pb >= 0 && boundaries_[pb].kind == BoundaryKind::pressure)
      phi_value_[n] = boundaries_[pb].pressure(xn, t);
  }
}

void FluidSolver::update_cell_coefficients() {
  const FluidSettings& s = settings_;
  const size_t nt = volume_.size();
  const double rdt = s.rho / s.dt;
  for (size_t t = 0; t < nt; ++t) {
    double wbar[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) wbar[d] += 0.25 * w_[3 * static_cast<size_t>(tet_nodes_[4 * t + a]) + d];
    const double speed = std::sqrt(wbar[0] * wbar[0] + wbar[1] * wbar[1] + wbar[2] * wbar[2]);
    const double h = h_[t], nu = s.mu / s.rho;
    // Orthogonal-subscale convection: tau_c free of dt, so a steady state does not depend on it
    // (kernels/fluid_convection_subscale.hpp).
    supg_tau_[t] = (s.supg && s.convection && speed > 0.0)
                       ? kernels::convection_subscale_tau(speed, h, nu, sigma_[t] / s.rho)
                       : 0.0;
    // Pressure stabilisation (orthogonal-subscale / gradient-projection form, Codina):
    //   tau_p = alpha / (4 mu/h^2 + 2 rho |w|/h + sigma)  [m^3 s/kg].
    // Dynamic: tau_t = 1 / (rho/dt + 1/tau_p) (also where tau_p is unbounded: an inviscid fluid at rest).
    const double denom = 4.0 * s.mu / (h * h) + (s.convection ? 2.0 * s.rho * speed / h : 0.0) + sigma_[t];
    const double alpha = s.pressure_stabilisation;
    if (!s.dynamic_subscale)
      tau_p_[t] = denom > 0.0 ? alpha / denom : 0.0;
    else
      tau_p_[t] = alpha > 0.0 ? alpha / (alpha * rdt + denom) : 0.0;
    c_cell_[t] = 1.0 / (rdt + sigma_[t]);
    pcoef_[t] = c_cell_[t] + tau_p_[t];
  }
  // Where the continuity is weighted down, the divergence of the flux c (f - grad p) of the fluid
  // relative to the solid (the momentum balance sigma (u - u_s) = f - grad p, with rho/dt) takes the
  // rest: (1 - w) c. The pressure there is the extension of the fluid's that lets no fluid through the
  // solid relative to it; hydrostatics stays exact.
  weighted_ = false;
  for (size_t t = 0; t < nt && !weighted_; ++t) weighted_ = continuity_weight_[t] != 1.0;
  if (weighted_) {
    relative_flux_.resize(nt);
    for (size_t t = 0; t < nt; ++t) relative_flux_[t] = (1.0 - continuity_weight_[t]) * c_cell_[t];
  }
  // Diagonal of the steady Schur complement M_L / mu + sum_t tau_p K^t (the viscous preconditioner part).
  for (size_t n = 0; n < node_volume_.size(); ++n) visc_diag_[n] = s.mu > 0.0 ? node_volume_[n] / s.mu : 0.0;
  for (size_t t = 0; t < nt; ++t) {
    const double* g = &grad_[12 * t];
    for (int a = 0; a < 4; ++a)
      visc_diag_[tet_nodes_[4 * t + a]] +=
          tau_p_[t] * volume_[t] *
          (g[3 * a] * g[3 * a] + g[3 * a + 1] * g[3 * a + 1] + g[3 * a + 2] * g[3 * a + 2]);
  }
  for (double& d : visc_diag_) d = d > 0.0 ? d : 1e300;
}

void FluidSolver::project_convective_derivative() {
  assembly_.convective_projection(tet_nodes_, volume_, grad_, w_, eta_);
  for (size_t n = 0; n < node_volume_.size(); ++n)
    for (int d = 0; d < 3; ++d) eta_[3 * n + d] /= node_volume_[n];
}

void FluidSolver::assemble_pressure_matrix() {
  assembly_.laplacian_matrix(
      {tet_nodes_, volume_, grad_, pcoef_, slot_, diag_slot_, phi_fixed_, phi_value_, pressure_mat_.val, {}});
  std::copy(pcoef_.begin(), pcoef_.end(), state(columns_.pressure_matrix_coefficient).begin());
  amg_->set_matrix(pressure_mat_);
  pressure_matrix_stale_ = false;
}

void FluidSolver::build_component_matrices() {
  const size_t nn = node_count();
  for (int d = 0; d < 3; ++d) {
    CsrMatrix& c = comp_[d];
    c.val = momentum_.val;
    for (size_t n = 0; n < nn; ++n)
      if (vel_fixed_by_[3 * n + d] != -1) {
        for (int32_t q = c.row_ptr[n]; q < c.row_ptr[n + 1]; ++q) c.val[q] = 0.0;
        c.val[diag_slot_[n]] = 1.0;
      }
  }
}

int FluidSolver::solve_momentum(std::span<const double> rhs3, std::span<double> u3, bool homogeneous,
                                double forcing) {
  const size_t nn = node_count();
  int its = 0;
  for (int d = 0; d < 3; ++d) {
    if (comp_all_fixed_[d]) {  // the system is the identity: u = the boundary values
      for (size_t n = 0; n < nn; ++n) u3[3 * n + d] = homogeneous ? 0.0 : vel_value_[3 * n + d];
      continue;
    }
    for (size_t n = 0; n < nn; ++n) {
      const bool fixed = vel_fixed_by_[3 * n + d] != -1;
      const double g = homogeneous ? 0.0 : vel_value_[3 * n + d];
      rhs_c_[n] = fixed ? g : rhs3[3 * n + d];
      x_c_[n] = fixed ? g : (homogeneous ? 0.0 : u_[3 * n + d]);
    }
    const KrylovResult kr = bicgstab_.solve(comp_[d], rhs_c_, x_c_, settings_.velocity_rel_tol, 1e-300,
                                            settings_.velocity_max_iterations, homogeneous ? 0.0 : forcing);
    its += kr.iterations;
    if (!kr.converged) ++momentum_failures_;
    for (size_t n = 0; n < nn; ++n) u3[3 * n + d] = x_c_[n];
  }
  return its;
}

kernels::PressureSubscaleArgs FluidSolver::subscale_args() const {
  return {tet_nodes_, volume_, grad_, tau_p_, settings_.rho / settings_.dt};
}

// The continuity residual is -sum_t (V/4)(div u_t - s_t) per node: the immersed solid's dilatation s
// (zero without one) adds +(V/4) s_t to each corner.
void FluidSolver::add_dilatation(std::span<double> residual) const {
  for (size_t t = 0; t < dilatation_.size(); ++t) {
    if (dilatation_[t] == 0.0 && volume_source_[t] == 0.0) continue;
    const double share = 0.25 * volume_[t] * (continuity_weight_[t] * dilatation_[t] + volume_source_[t]);
    for (int q = 0; q < 4; ++q) residual[static_cast<size_t>(tet_nodes_[4 * t + q])] += share;
  }
}

void FluidSolver::schur_velocity(std::span<const double> v, std::span<double> u_v, int& velocity_iterations) {
  assembly_.weighted_gradient({tet_nodes_, volume_, grad_, v, {}}, grad_v_);
  for (double& g : grad_v_) g = -g;
  velocity_iterations += solve_momentum(grad_v_, u_v, true);
}

// S v = R(u_v, v) - R(0, 0) with u_v = A^-1 (-G v): the Schur complement of the stabilised system; rows of
// fixed pressure nodes are the identity.
void FluidSolver::schur_apply(std::span<const double> v, std::span<double> sv, SchurStats& st) {
  const size_t nn = node_count();
  schur_velocity(v, u_v_, st.velocity_iterations);
  // The projected gradient xi(v) = M_L^-1 int N grad v is linear in v: it is part of the operator, so the
  // stabilisation tau_p (grad q, grad p - xi(p)) is implicit (grad_v_ holds int N grad v * -1 here).
  for (size_t n = 0; n < nn; ++n)
    for (int d = 0; d < 3; ++d) xi_v_[3 * n + d] = -grad_v_[3 * n + d] / node_volume_[n];
  assembly_.pressure_rhs(
      {tet_nodes_, volume_, grad_, u_v_, v, xi_v_, tau_p_, continuity_weights(), relative_flux()}, sv);
  for (size_t n = 0; n < nn; ++n) sv[n] = phi_fixed_[n] && !closed_ ? v[n] : -sv[n];
}

// Cahouet-Chabard-type preconditioner: z = [(c + tau_p) K]^-1 r + chi r / diag(M_L/mu + tau_p K).
void FluidSolver::schur_precondition(std::span<const double> r, std::span<double> z, SchurStats& st) {
  const size_t nn = node_count();
  for (size_t n = 0; n < nn; ++n) {
    prec_rhs_[n] = phi_fixed_[n] ? 0.0 : r[n];
    z[n] = 0.0;
  }
  const AmgPcgResult pr = amg_->solve(prec_rhs_, z);
  st.pressure_iterations += pr.iterations;
  double mean = 0.0;
  for (size_t n = 0; n < nn; ++n) {
    z[n] = phi_fixed_[n] && !closed_ ? r[n] : z[n] + settings_.viscous_correction * r[n] / visc_diag_[n];
    mean += z[n];
  }
  if (closed_)
    for (size_t n = 0; n < nn; ++n) z[n] -= mean / static_cast<double>(nn);
}

// S delta = b by flexible GMRES (engine/linear/fgmres.hpp), delta = 0 on entry.
FluidSolver::SchurStats FluidSolver::schur_solve(std::span<const double> b, std::span<double> delta) {
  SchurStats st;
  double beta = 0.0;
  for (double v : b) beta += v * v;
  beta = std::sqrt(beta);
  // Relative to the largest initial residual of this step, so a Picard iterate that is already converged
  // costs no iterations.
  schur_reference_ = std::max(schur_reference_, beta);
  st.target = std::max({settings_.schur_rel_tol * schur_reference_, schur_floor_, 1e-300});
  const KrylovResult r = fgmres_.solve([&](auto v, auto w) { schur_apply(v, w, st); },
                                       [&](auto v, auto z) { schur_precondition(v, z, st); }, b, delta,
                                       st.target, settings_.schur_max_iterations);
  st.iterations = r.iterations;
  st.residual = r.residual;
  st.converged = r.converged;
  return st;
}

// max|u|, but at least the speed sqrt(pressure range / rho) the pressure differences could drive: in a fluid
// at rest (hydrostatic, or around a solid at rest) u is round-off, and a change relative to it alone never
// falls below a tolerance.
double FluidSolver::velocity_scale(std::span<const double> u, std::span<const double> p) const {
  const double umax = max_abs(u);
  if (p.empty()) return umax;
  const auto [pmin, pmax] = std::minmax_element(p.begin(), p.end());
  return std::max(umax, std::sqrt((*pmax - *pmin) / settings_.rho));
}

FluidStepReport FluidSolver::advance() {
  const FluidSettings& s = settings_;
  const size_t nn = node_count(), nt = volume_.size();
  const double t_new = time_ + s.dt;
  FluidStepReport rep;
  const int momentum_failures_at_start = momentum_failures_;
  schur_reference_ = 0.0;
  // The iterates live in the spares; u^n and p^n stay as committed.
  u_old_ = state(columns_.velocity);
  const std::span<const double> p_n = state(columns_.pressure);
  u_ = next_velocity_.values<double>();
  p_ = next_pressure_.values<double>();
  const std::span<double> pcoef_matrix = state(columns_.pressure_matrix_coefficient);
  const std::span<double> subscale = state(columns_.pressure_subscale);
  apply_velocity_bc(t_new);
  schur_floor_ = 1e-12 * velocity_scale(u_old_, p_n) * residual_area_;
  if (s.picard_extrapolate && has_previous()) {
    // First iterate 2 u^n - u^{n-1}, boundary values at t^{n+1}.
    const std::span<const double> u_prev = state(columns_.previous_velocity);
    for (size_t i = 0; i < 3 * nn; ++i)
      u_[i] = vel_fixed_by_[i] != -1 ? vel_value_[i] : 2.0 * u_old_[i] - u_prev[i];
  } else {
    std::copy(u_old_.begin(), u_old_.end(), u_.begin());
  }
  std::copy(p_n.begin(), p_n.end(), p_.begin());
  if (body_force_fn_) {
    for (size_t n = 0; n < nn; ++n) {
      const Vec3 xn{x_[3 * n], x_[3 * n + 1], x_[3 * n + 2]};
      const Vec3 f0 = body_force_fn_(xn, time_), f1 = body_force_fn_(xn, t_new);
      for (int d = 0; d < 3; ++d) body_force_[3 * n + d] = s.theta * f1[d] + (1.0 - s.theta) * f0[d];
    }
  }
  // Pressure at Dirichlet nodes: the boundary value at t^{n+1}.
  for (size_t n = 0; n < nn; ++n)
    if (pressure_fixed_by_[n] >= 0) p_[n] = phi_value_[n];
  // Projected pressure gradient of p^n.
  const auto project_gradient = [&] {
    assembly_.weighted_gradient({tet_nodes_, volume_, grad_, p_, {}}, xi_);
    for (size_t n = 0; n < nn; ++n)
      for (int d = 0; d < 3; ++d) xi_[3 * n + d] /= node_volume_[n];
  };
  project_gradient();

  for (int k = 0; k < s.picard_max_iterations; ++k) {
    std::copy(u_.begin(), u_.end(), u_iter_.begin());
    std::copy(p_.begin(), p_.end(), p_iter_.begin());
    for (size_t i = 0; i < 3 * nn; ++i)
      w_[i] = s.convection ? s.theta * u_[i] + (1.0 - s.theta) * u_old_[i] : 0.0;
    if (s.supg && s.convection) project_convective_derivative();
    if (k == 0) {
      update_cell_coefficients();
      // The pressure matrix only preconditions the fixed-point iteration (its solution does not depend on
      // it), so it is rebuilt only when a coefficient drifted by more than 25 % since the last build.
      bool drift = pressure_matrix_stale_;
      for (size_t t = 0; t < nt && !drift; ++t)
        drift = std::abs(pcoef_[t] - pcoef_matrix[t]) > 0.25 * pcoef_matrix[t];
      if (drift) {
        assemble_pressure_matrix();
        ++rep.amg_setups;
      }
      if (s.dynamic_subscale) {
        std::fill(subscale_rhs_.begin(), subscale_rhs_.end(), 0.0);
        kernels::pressure_subscale_rhs(subscale_args(), subscale, subscale_rhs_);
      }
    }
    const int momentum_failures_before = momentum_failures_;
    bool schur_converged = true;
    // 1. Momentum.
    kernels::FluidMomentumArgs ma;
    ma.rho = s.rho;
    ma.mu = s.mu;
    ma.dt = s.dt;
    ma.theta = s.theta;
    ma.tet_nodes = tet_nodes_;
    ma.volume = volume_;
    ma.grad = grad_;
    ma.slot = slot_;
    ma.u_old = u_old_;
    ma.advect = w_;
    ma.pressure = p_;
    ma.supg_tau = supg_tau_;
    if (s.supg && s.convection) ma.convection_projection = eta_;
    ma.sigma = sigma_;
    ma.target = target_;
    ma.source = source_;
    if (body_force_fn_) ma.body_force = body_force_;
    ma.matrix_values = momentum_.val;
    ma.rhs = rhs_;
    assembly_.momentum(ma);
    build_component_matrices();
    rep.velocity_iterations += solve_momentum(rhs_, u_star_, false, s.velocity_forcing);
    // 2. Pressure: residual -R(u*, p^k) of the stabilised continuity equation.
    assembly_.pressure_rhs(
        {tet_nodes_, volume_, grad_, u_star_, p_, xi_, tau_p_, continuity_weights(), relative_flux(),
         body_force_fn_ && weighted_ ? std::span<const double>(body_force_) : std::span<const double>{}},
        cont_res_);
    add_dilatation(cont_res_);
    if (s.dynamic_subscale)
      for (size_t n = 0; n < nn; ++n) cont_res_[n] += subscale_rhs_[n];
    if (s.coupling == PressureCoupling::schur_gmres) {
      double sum = 0.0;
      for (size_t n = 0; n < nn; ++n) {
        prhs_[n] = phi_fixed_[n] && !closed_ ? 0.0 : cont_res_[n];
        sum += prhs_[n];
      }
      if (closed_)
        for (double& r : prhs_) r -= sum / static_cast<double>(nn);
      std::fill(phi_.begin(), phi_.end(), 0.0);
      const SchurStats st = schur_solve(prhs_, phi_);
      rep.velocity_iterations += st.velocity_iterations;
      rep.pressure_iterations += st.pressure_iterations;
      rep.schur_iterations += st.iterations;
      schur_converged = st.converged;
      if (!st.converged) {
        rep.schur_residual = st.residual;
        rep.schur_target = st.target;
      }
      // u = u* + A^-1 (-G delta): one more homogeneous momentum solve.
      schur_velocity(phi_, corr_, rep.velocity_iterations);
      for (size_t i = 0; i < 3 * nn; ++i) u_[i] = u_star_[i] + corr_[i];
      for (size_t n = 0; n < nn; ++n) p_[n] = pressure_fixed_by_[n] >= 0 ? phi_value_[n] : p_[n] + phi_[n];
      if (closed_) {
        double pv = 0.0, vol = 0.0;
        for (size_t n = 0; n < nn; ++n) {
          pv += node_volume_[n] * p_[n];
          vol += node_volume_[n];
        }
        for (double& pn : p_) pn -= pv / vol;
      }
    } else {
      prhs_ = cont_res_;
      std::fill(phi_.begin(), phi_.end(), 0.0);
      std::vector<double>& phi_bc = corr_;  // reuse: Dirichlet values of phi (first nn entries)
      for (size_t n = 0; n < nn; ++n) phi_bc[n] = pressure_fixed_by_[n] >= 0 ? phi_value_[n] - p_[n] : 0.0;
      kernels::scalar_laplacian_dirichlet_rhs({tet_nodes_,
                                               volume_,
                                               grad_,
                                               pcoef_matrix,
                                               slot_,
                                               diag_slot_,
                                               phi_fixed_,
                                               std::span<const double>(phi_bc.data(), nn),
                                               {},
                                               prhs_});
      for (size_t n = 0; n < nn; ++n)
        if (phi_fixed_[n]) phi_[n] = phi_bc[n];
      const AmgPcgResult pr =
          amg_->solve(prhs_, phi_, std::max(s.pressure_solver.rel_tol, s.projection_forcing));
      rep.pressure_iterations += pr.iterations;
      // 3. Corrections: u = u* - c grad phi (lumped), p += phi - chi R / diag(S_steady).
      assembly_.weighted_gradient({tet_nodes_, volume_, grad_, phi_, c_cell_}, corr_);
      for (size_t n = 0; n < nn; ++n) {
        for (int d = 0; d < 3; ++d) {
          const size_t i = 3 * n + d;
          u_[i] = vel_fixed_by_[i] != -1 ? vel_value_[i] : u_star_[i] - corr_[i] / node_volume_[n];
        }
        if (pressure_fixed_by_[n] >= 0)
          p_[n] = phi_value_[n];
        else
          p_[n] += phi_[n] + s.projection_viscous_correction * cont_res_[n] / visc_diag_[n];
      }
    }
    project_gradient();
    // Convergence.
    double du = 0.0, dp = 0.0;
    for (size_t i = 0; i < 3 * nn; ++i) du = std::max(du, std::abs(u_[i] - u_iter_[i]));
    for (size_t n = 0; n < nn; ++n) dp = std::max(dp, std::abs(p_[n] - p_iter_[n]));
    const double umax = max_abs(u_);
    rep.velocity_change = du / std::max(velocity_scale(u_, p_), 1e-300);
    rep.pressure_change = dp / std::max({max_abs(p_), s.rho * umax * umax, 1e-300});
    rep.picard_iterations = k + 1;
    if (s.verbose)
      std::fprintf(stderr,
                   "  picard %d du %.3e dp %.3e umax %.3e pmax %.3e vits %d pits %d schur %d setups %d\n", k,
                   rep.velocity_change, rep.pressure_change, umax, max_abs(p_), rep.velocity_iterations,
                   rep.pressure_iterations, rep.schur_iterations, rep.amg_setups);
    rep.linear_converged = schur_converged && momentum_failures_ == momentum_failures_before;
    if (rep.velocity_change <= s.picard_tol && rep.pressure_change <= s.picard_tol && rep.linear_converged) {
      rep.converged = true;
      break;
    }
  }
  rep.momentum_failures = momentum_failures_ - momentum_failures_at_start;
  // The subscale at t^{n+1} from the final p and its projected gradient (xi_ is that of p_).
  if (s.dynamic_subscale) kernels::pressure_subscale_update(subscale_args(), p_, xi_, subscale);
  // Diagnostics of u^{n+1}.
  kernels::p1_divergence(tet_nodes_, grad_, u_, div_);
  double l2 = 0.0;
  for (size_t t = 0; t < nt; ++t) {
    l2 += volume_[t] * div_[t] * div_[t];
    rep.divergence_max = std::max(rep.divergence_max, std::abs(div_[t]));
    double ubar[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) ubar[d] += 0.25 * u_[3 * static_cast<size_t>(tet_nodes_[4 * t + a]) + d];
    const double speed = std::sqrt(ubar[0] * ubar[0] + ubar[1] * ubar[1] + ubar[2] * ubar[2]);
    rep.cfl = std::max(rep.cfl, speed * s.dt / h_[t]);
  }
  rep.divergence_l2 = std::sqrt(l2);
  time_ = t_new;
  return rep;
}

void FluidSolver::commit() {
  columns_.previous_velocity->swap_values(*columns_.velocity);  // u^{n-1} <- u^n
  columns_.velocity->swap_values(next_velocity_);               // u^n <- u^{n+1}; the spare: old u^{n-1}
  columns_.pressure->swap_values(next_pressure_);
  columns_.has_previous->values<uint8_t>()[0] = 1;
}

void FluidSolver::restored(double t) {
  time_ = t;
  apply_velocity_bc(time_);
  const std::span<const double> coefficients = state(columns_.pressure_matrix_coefficient);
  bool assembled = false;
  for (double c : coefficients) assembled = assembled || c != 0.0;
  if (assembled) {
    std::copy(coefficients.begin(), coefficients.end(), pcoef_.begin());
    assemble_pressure_matrix();
  } else {
    pressure_matrix_stale_ = true;
  }
}

}  // namespace rift::fluid
