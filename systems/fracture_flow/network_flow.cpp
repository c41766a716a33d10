#include "systems/fracture_flow/network_flow.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rift {

NetworkFlow::NetworkFlow(kernels::FluidEos eos, double viscosity, double lag_pressure, NetworkSolver solver)
    : eos_(eos), viscosity_(viscosity), lag_pressure_(lag_pressure), solver_kind_(solver) {
  cg_.setTolerance(1e-10);
}

void NetworkFlow::set_network(std::span<const int32_t> triangles, size_t vertex_count) {
  vertices_ = vertex_count;
  triangles_.assign(triangles.begin(), triangles.end());
  const size_t nt = triangles_.size() / 3;
  // Edges as sorted vertex pairs, numbered in sorted order (independent of the triangles' order).
  // A triangle may have two corners on one vertex (a borehole well gathers every wall point into one):
  // the edge between them joins a vertex to itself and carries nothing, so it is left out (key -1).
  std::vector<int64_t> keys(3 * nt);
  auto key = [&](int32_t a, int32_t b) {
    return a == b ? int64_t(-1) : int64_t(std::min(a, b)) * int64_t(vertex_count) + std::max(a, b);
  };
  for (size_t t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c)
      keys[3 * t + c] = key(triangles_[3 * t + (c + 1) % 3], triangles_[3 * t + (c + 2) % 3]);
  std::vector<int64_t> unique_keys = keys;
  std::sort(unique_keys.begin(), unique_keys.end());
  unique_keys.erase(std::unique(unique_keys.begin(), unique_keys.end()), unique_keys.end());
  if (!unique_keys.empty() && unique_keys.front() < 0) unique_keys.erase(unique_keys.begin());
  edge_v_.resize(2 * unique_keys.size());
  for (size_t e = 0; e < unique_keys.size(); ++e) {
    edge_v_[2 * e] = int32_t(unique_keys[e] / int64_t(vertex_count));
    edge_v_[2 * e + 1] = int32_t(unique_keys[e] % int64_t(vertex_count));
  }
  triangle_edge_.resize(3 * nt);
  for (size_t k = 0; k < keys.size(); ++k)
    triangle_edge_[k] = keys[k] < 0
                            ? -1
                            : int32_t(std::lower_bound(unique_keys.begin(), unique_keys.end(), keys[k]) -
                                      unique_keys.begin());
  transmissibility_.assign(unique_keys.size(), 0.0);
  edge_density_.assign(unique_keys.size(), 0.0);
  vertex_density_.assign(vertex_count, 0.0);
  new_pressure_.assign(vertex_count, 0.0);

  // The matrix's pattern: the diagonal and every edge (upper triangle is enough for LDLT, but Eigen's
  // SimplicialLDLT reads the lower one by default: store j >= i as (row j, column i)).
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t v = 0; v < vertex_count; ++v) entries.emplace_back(int(v), int(v), 1.0);
  for (size_t e = 0; e < edge_count(); ++e) entries.emplace_back(edge_v_[2 * e + 1], edge_v_[2 * e], 1.0);
  matrix_.resize(int(vertex_count), int(vertex_count));
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  diagonal_slot_.assign(vertex_count, -1);
  edge_slot_.assign(edge_count(), -1);
  const int* outer = matrix_.outerIndexPtr();
  const int* inner = matrix_.innerIndexPtr();
  for (int col = 0; col < matrix_.outerSize(); ++col)
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      if (inner[k] == col) {
        diagonal_slot_[size_t(col)] = k;
      } else {
        const int64_t kk = key(col, inner[k]);
        edge_slot_[size_t(std::lower_bound(unique_keys.begin(), unique_keys.end(), kk) -
                          unique_keys.begin())] = k;
      }
    }
  use_cg_ = solver_kind_ == NetworkSolver::cg ||
            (solver_kind_ == NetworkSolver::automatic && vertex_count >= kDirectVertices);
  cg_.setMaxIterations(int(std::max<size_t>(200, vertex_count)));
  if (!use_cg_) solver_.analyzePattern(matrix_);
  rhs_.setZero(int(vertex_count));
  solution_.setZero(int(vertex_count));
}

void NetworkFlow::transmissibilities(const NetworkFlowStepInput& in) {
  std::fill(transmissibility_.begin(), transmissibility_.end(), 0.0);
  const size_t nt = triangles_.size() / 3;
  for (size_t t = 0; t < nt; ++t) {
    double k[3];
    kernels::p1_edge_coefficients(&in.triangle_x[9 * t], &in.triangle_x[9 * t + 3], &in.triangle_x[9 * t + 6],
                                  k);
    const double w = (in.aperture[3 * t] + in.aperture[3 * t + 1] + in.aperture[3 * t + 2]) / 3.0;
    const double c = w * w * w / (12.0 * viscosity_);
    for (int i = 0; i < 3; ++i)
      if (triangle_edge_[3 * t + i] >= 0) transmissibility_[size_t(triangle_edge_[3 * t + i])] -= c * k[i];
  }
  negative_ = size_t(
      std::count_if(transmissibility_.begin(), transmissibility_.end(), [](double T) { return T < 0.0; }));
}

// The fluid's density on each edge, the mean of its ends' at the step's old pressures: the same in every
// pass of the step's active sets, so computed once (the equation of state divides).
void NetworkFlow::edge_densities(const NetworkFlowState& s) {
  for (size_t v = 0; v < vertices_; ++v) vertex_density_[v] = eos_.density(s.pressure[v]);
  for (size_t e = 0; e < edge_count(); ++e)
    edge_density_[e] =
        0.5 * (vertex_density_[size_t(edge_v_[2 * e])] + vertex_density_[size_t(edge_v_[2 * e + 1])]);
}

// The P1 transmissibility, except at the front (an end dry or filling): there a negative one (an obtuse angle
// opposite the edge) would pull fluid out of a vertex at the lag pressure, which holds none to give, so
// it is taken as zero.
double NetworkFlow::edge_transmissibility(size_t e, const NetworkFlowState& s) const {
  const double T = transmissibility_[e];
  if (T >= 0.0) return T;
  auto holds = [&](int32_t v) { return FlowRole(s.role[size_t(v)]) >= FlowRole::wet; };  // wet or fixed
  return holds(edge_v_[2 * e]) && holds(edge_v_[2 * e + 1]) ? T : 0.0;
}

std::string NetworkFlow::solve_pressures(const NetworkFlowStepInput& in, const NetworkFlowState& s) {
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  for (size_t v = 0; v < vertices_; ++v) {
    const auto role = FlowRole(s.role[v]);
    if (role != FlowRole::wet) {
      values[diagonal_slot_[v]] = 1.0;
      new_pressure_[v] = role == FlowRole::fixed ? in.fixed_pressure[v] : lag_pressure_;
      rhs_[int(v)] = new_pressure_[v];
      continue;
    }
    const double p = s.pressure[v], rho = vertex_density_[v];
    const double storage =
        eos_.density0 / eos_.bulk_modulus * volume_at(in, v, p) + rho * compliance_at(in, v);
    values[diagonal_slot_[v]] = storage;
    rhs_[int(v)] = storage * p + s.mass[v] - rho * volume_at(in, v, p) + in.dt * in.source[v];
  }
  for (size_t e = 0; e < edge_count(); ++e) {
    const size_t i = size_t(edge_v_[2 * e]), j = size_t(edge_v_[2 * e + 1]);
    const bool wi = FlowRole(s.role[i]) == FlowRole::wet, wj = FlowRole(s.role[j]) == FlowRole::wet;
    const double a = in.dt * edge_density_[e] * edge_transmissibility(e, s);
    if (wi) values[diagonal_slot_[i]] += a;
    if (wj) values[diagonal_slot_[j]] += a;
    if (wi && wj) values[edge_slot_[e]] = -a;
    if (wi && !wj) rhs_[int(i)] += a * new_pressure_[j];
    if (wj && !wi) rhs_[int(j)] += a * new_pressure_[i];
  }
  if (use_cg_) {
    // CG's tolerance is on the residual's norm against the right-hand side's: rows that hold a pressure
    // (1 x p = p, with p ~ 1e6 Pa) would dwarf the mass balance rows (storage ~ 1e-15 kg/Pa) and make the
    // tolerance meaningless for them. Scaled to the largest diagonal of a balance row, they weigh alike.
    double scale = 0.0;
    for (size_t v = 0; v < vertices_; ++v)
      if (FlowRole(s.role[v]) == FlowRole::wet) scale = std::max(scale, values[diagonal_slot_[v]]);
    if (scale > 0.0)
      for (size_t v = 0; v < vertices_; ++v)
        if (FlowRole(s.role[v]) != FlowRole::wet) {
          values[diagonal_slot_[v]] = scale;
          rhs_[int(v)] = scale * new_pressure_[v];
        }
    // Started from the pressures of the last step (and the held values where they are held).
    for (size_t v = 0; v < vertices_; ++v)
      solution_[int(v)] = FlowRole(s.role[v]) == FlowRole::wet ? s.pressure[v] : new_pressure_[v];
    cg_.compute(matrix_);
    if (cg_.info() != Eigen::Success)
      return "the fracture flow's preconditioner failed (a zero on the diagonal)";
    solution_ = cg_.solveWithGuess(rhs_, solution_);
    cg_iterations_ = int(cg_.iterations());
    if (cg_.info() != Eigen::Success)
      return fmt::format(
          "the fracture flow's conjugate gradients did not converge in {} iterations (relative residual "
          "{:.3g}, asked 1e-10); set fracture_flow.solver: direct",
          cg_.iterations(), cg_.error());
  } else {
    solver_.factorize(matrix_);
    if (solver_.info() != Eigen::Success)
      return "the fracture flow's matrix could not be factorised (not positive definite: an obtuse crack "
             "triangle's negative transmissibility outweighs the storage)";
    solution_ = solver_.solve(rhs_);
    cg_iterations_ = 0;
  }
  for (size_t v = 0; v < vertices_; ++v) {
    if (FlowRole(s.role[v]) != FlowRole::wet) continue;  // held: new_pressure_ has its value
    if (!std::isfinite(solution_[int(v)]))
      return fmt::format("the fracture flow's pressure at vertex {} is not finite", v);
    new_pressure_[v] = solution_[int(v)];
  }
  return "";
}

void NetworkFlow::start_step() {
  stage_.assign(vertices_, uint8_t(Closing::open));
}

double NetworkFlow::stage_compliance(const NetworkFlowStepInput& in, size_t v, Closing stage) {
  return stage == Closing::open           ? in.compliance[v]
         : stage == Closing::open_corners ? in.compliance_open[v]
                                          : 0.0;
}

// The walls' volume at p under a stage, and whether a vertex at p holds at least its floor under it: for a
// fixed vertex (refilled to its pressure exactly) by its volume; for a wet one also by the mass the step's
// linearised balance leaves it, rho V at its old pressure plus the storage times the change, which falls
// short of rho(p) V(p) by (rho0 / K_f) C dp^2: where walls far more compliant than the fluid nearly close
// within the step, a volume just above the floor can come with a negative mass.
bool NetworkFlow::stage_holds(const NetworkFlowStepInput& in, const NetworkFlowState& s, size_t v, double p,
                              Closing stage) const {
  if (stage == Closing::closed) return true;
  const double c = stage_compliance(in, v, stage);
  const double floor = in.floor_volume[v];
  if (in.volume[v] + c * (p - in.applied[v]) < floor) return false;
  if (FlowRole(s.role[v]) == FlowRole::fixed) return true;
  const double p_old = s.pressure[v], v_old = in.volume[v] + c * (p_old - in.applied[v]);
  const double storage = eos_.density0 / eos_.bulk_modulus * v_old + eos_.density(p_old) * c;
  return eos_.density(p_old) * v_old + storage * (p - p_old) >= eos_.density(p) * floor;
}

NetworkFlow::Closing NetworkFlow::stage_at(const NetworkFlowStepInput& in, const NetworkFlowState& s,
                                           size_t v, double p) const {
  for (Closing c : {Closing::open, Closing::open_corners})
    if (stage_holds(in, s, v, p, c)) return c;
  return Closing::closed;
}

void NetworkFlow::close_fixed(const NetworkFlowStepInput& in, const NetworkFlowState& s) {
  if (in.floor_volume.empty()) return;
  for (size_t v = 0; v < vertices_; ++v)
    if (FlowRole(s.role[v]) == FlowRole::fixed) stage_[v] = uint8_t(stage_at(in, s, v, in.fixed_pressure[v]));
}

void NetworkFlow::finish_step(const NetworkFlowStepInput& in, const NetworkFlowState& s) {
  volume_used_.resize(vertices_);
  wall_pressure_.resize(vertices_);
  for (size_t v = 0; v < vertices_; ++v) {
    volume_used_[v] = volume_at(in, v, s.pressure[v]);
    wall_pressure_[v] = s.pressure[v];
    if (Closing(stage_[v]) == Closing::closed)
      wall_pressure_[v] = in.compliance_open[v] > 0.0
                              ? in.applied[v] + (in.floor_volume[v] - in.volume[v]) / in.compliance_open[v]
                              : in.applied[v];
  }
}

std::string NetworkFlow::step(const NetworkFlowStepInput& in, NetworkFlowState& s, NetworkFlowBooks& books) {
  start_step();
  if (viscosity_ <= 0.0) return zero_viscosity_step(in, s, books);
  close_fixed(in, s);
  transmissibilities(in);
  edge_densities(s);
  // Two active sets, solved again until neither changes:
  // - cavitation: a wet vertex whose pressure would fall below the lag pressure holds the lag pressure, so
  //   that no fluid is drawn from a vertex that cannot give it (one way: wet to filling);
  // - closing: a wet vertex takes the first of its stages that holds its floor at the new pressure (all
  //   corners' compliance; its open corners' only, since a floored corner's volume does not follow its
  //   nodes; closed onto the floor, whose walls close no further within the step). The stage follows
  //   the pressure both ways: a vertex judged closing in one pass (its neighbours still wet) may be fed
  //   in the next (they cavitated) and must open again, or an injection into it would find rigid walls.
  //   After kFreePasses passes a stage only moves down, so the passes end.
  for (size_t pass = 0;; ++pass) {
    if (std::string problem = solve_pressures(in, s); !problem.empty()) return problem;
    size_t changed = 0;
    for (size_t v = 0; v < vertices_; ++v) {
      if (FlowRole(s.role[v]) != FlowRole::wet) continue;
      if (new_pressure_[v] < lag_pressure_) {
        s.role[v] = uint8_t(FlowRole::filling);
        ++changed;
        continue;
      }
      if (in.floor_volume.empty()) continue;
      const Closing stage = stage_at(in, s, v, new_pressure_[v]);
      if (stage != Closing(stage_[v]) && (pass < kFreePasses || stage > Closing(stage_[v]))) {
        stage_[v] = uint8_t(stage);
        ++changed;
      }
    }
    if (changed == 0) break;
    if (pass > kFreePasses + 3 * vertices_) return "the fracture flow's cavitation passes did not settle";
  }
  // Mass over the step along each edge, from i to j; fluid leaves only a wet or a fixed vertex.
  auto mobile = [&](size_t v) {
    return FlowRole(s.role[v]) == FlowRole::wet || FlowRole(s.role[v]) == FlowRole::fixed;
  };
  for (size_t e = 0; e < edge_count(); ++e) {
    const size_t i = size_t(edge_v_[2 * e]), j = size_t(edge_v_[2 * e + 1]);
    const double dp = new_pressure_[i] - new_pressure_[j];
    const double T = edge_transmissibility(e, s);
    double flux = in.dt * edge_density_[e] * T * dp;
    if ((flux > 0.0 && !mobile(i)) || (flux < 0.0 && !mobile(j))) flux = 0.0;
    s.mass[i] -= flux;
    s.mass[j] += flux;
    if (flux != 0.0) books.dissipation += in.dt * T * dp * dp;
  }
  for (size_t v = 0; v < vertices_; ++v) {
    s.mass[v] += in.dt * in.source[v];
    books.sourced += in.dt * in.source[v];
  }
  return update_roles(in, s, true);
}

std::string NetworkFlow::local_step(const NetworkFlowStepInput& in, NetworkFlowState& s) {
  start_step();
  close_fixed(in, s);
  return update_roles(in, s, false);
}

std::string NetworkFlow::update_roles(const NetworkFlowStepInput& in, NetworkFlowState& s, bool from_solve) {
  for (size_t v = 0; v < vertices_; ++v) {
    auto role = FlowRole(s.role[v]);
    if (role == FlowRole::fixed) {
      const double p = in.fixed_pressure[v];
      const double full = eos_.density(p) * volume_at(in, v, p);
      s.exchanged[v] += full - s.mass[v];
      s.mass[v] = full;
      s.pressure[v] = p;
      continue;
    }
    if (s.mass[v] < 0.0)
      return fmt::format("the fracture flow drew more fluid out of vertex {} than it held ({:.6g} kg)", v,
                         s.mass[v]);
    if (role == FlowRole::dry && s.mass[v] > 0.0) {
      role = FlowRole::filling;
      s.wetting_time[v] = in.time;
    }
    if (role == FlowRole::filling &&
        s.mass[v] >= eos_.density(lag_pressure_) * volume_at(in, v, lag_pressure_))
      role = FlowRole::wet;
    // A vertex wet through the step keeps the solve's pressure: its mass moved conservatively with the
    // fluxes of that pressure, and the small difference rho(p) V(p) - m (second order in the step) enters
    // the next step's right-hand side, so it does not accumulate. Inverting the equation of state instead
    // would amplify the mass's rounding by K_f / (rho0 V) for a stiff fluid in a rigid crack. A vertex
    // that has just filled takes the pressure of its mass, with all its corners' compliance (its walls
    // open under the fluid's arrival, whatever stage the solve's passes gave it while it held the lag
    // pressure).
    double p = lag_pressure_;
    if (role == FlowRole::wet && from_solve && FlowRole(s.role[v]) == FlowRole::wet) {
      p = new_pressure_[v];
    } else if (role == FlowRole::wet) {
      stage_[v] = uint8_t(Closing::open);
      p = kernels::pressure_of_mass(eos_, s.mass[v], in.volume[v], in.compliance[v], in.applied[v]);
    }
    if (role == FlowRole::wet && p < lag_pressure_) {
      role = FlowRole::filling;
      p = lag_pressure_;
    }
    if (!std::isfinite(p)) return fmt::format("the fracture flow's pressure at vertex {} is not finite", v);
    s.pressure[v] = p;
    s.role[v] = uint8_t(role);
  }
  finish_step(in, s);
  return "";
}

// Zero viscosity: the fluid levels out at once over each connected part of the network, which then has
// one pressure: that of its fixed vertex if it has one, else the root of rho(p) sum V(p) = its mass.
std::string NetworkFlow::zero_viscosity_step(const NetworkFlowStepInput& in, NetworkFlowState& s,
                                             NetworkFlowBooks& books) {
  component_.resize(vertices_);
  std::iota(component_.begin(), component_.end(), 0);
  auto find = [&](int32_t v) {
    while (component_[size_t(v)] != v) v = component_[size_t(v)] = component_[size_t(component_[size_t(v)])];
    return v;
  };
  for (size_t t = 0; t < triangles_.size() / 3; ++t)
    for (int c = 1; c < 3; ++c) {
      const int32_t a = find(triangles_[3 * t]), b = find(triangles_[3 * t + size_t(c)]);
      if (a != b) component_[size_t(std::max(a, b))] = std::min(a, b);  // the root is the lowest vertex
    }
  // Per component (indexed by its root): mass, V0 and C of V(p) = V0 + C p, its first fixed vertex; kept in
  // members so that the step allocates nothing once sized.
  std::vector<double>& mass = part_mass_;
  std::vector<double>& v0 = part_v0_;
  std::vector<double>& comp = part_compliance_;
  std::vector<int64_t>& fixed_vertex = part_fixed_;
  mass.assign(vertices_, 0.0);
  v0.assign(vertices_, 0.0);
  comp.assign(vertices_, 0.0);
  fixed_vertex.assign(vertices_, -1);
  for (size_t v = 0; v < vertices_; ++v) {
    const size_t r = size_t(find(int32_t(v)));
    s.mass[v] += in.dt * in.source[v];
    books.sourced += in.dt * in.source[v];
    mass[r] += s.mass[v];
    v0[r] += in.volume[v] - in.compliance[v] * in.applied[v];
    comp[r] += in.compliance[v];
    if (FlowRole(s.role[v]) == FlowRole::fixed && fixed_vertex[r] < 0) fixed_vertex[r] = int64_t(v);
  }
  // fill[r]: the share of its volume at the lag pressure that a sealed part's fluid fills when it cannot
  // fill it all (new crack space opened faster than the fluid, incompressible as it nearly is, can follow):
  // the part then holds the lag pressure, like the lag ahead of a viscous front. 1: full.
  std::vector<double>& fill = v0;  // v0 is not needed once the pressures are known
  for (size_t r = 0; r < vertices_; ++r) {
    if (size_t(find(int32_t(r))) != r) continue;
    new_pressure_[r] = fixed_vertex[r] >= 0 ? in.fixed_pressure[size_t(fixed_vertex[r])]
                                            : kernels::pressure_of_mass(eos_, mass[r], v0[r], comp[r], 0.0);
    const double room = eos_.density(lag_pressure_) * (v0[r] + comp[r] * lag_pressure_);
    fill[r] = 1.0;
    if (fixed_vertex[r] < 0 && new_pressure_[r] < lag_pressure_) {
      new_pressure_[r] = lag_pressure_;
      fill[r] = mass[r] / room;
    }
    if (!std::isfinite(new_pressure_[r]))
      return fmt::format("the fracture flow's pressure of the part holding vertex {} is not finite", r);
  }
  // Every vertex full (or filled to its part's share) at its part's pressure. A sealed part's total is
  // unchanged up to rounding; a part with a fixed vertex books what it gained or lost as that vertex's
  // exchange.
  for (size_t v = 0; v < vertices_; ++v) {
    const size_t r = size_t(find(int32_t(v)));
    const double p = new_pressure_[r];
    s.mass[v] = fill[r] * eos_.density(p) * volume_at(in, v, p);
    s.pressure[v] = p;
    if (fixed_vertex[r] >= 0) mass[r] -= s.mass[v];
    // A part with no fluid at all (a crack that opened apart from the others) stays dry.
    const bool reached = s.mass[v] > 0.0;
    if (FlowRole(s.role[v]) == FlowRole::dry && reached) s.wetting_time[v] = in.time;
    if (FlowRole(s.role[v]) != FlowRole::fixed)
      s.role[v] = uint8_t(fill[r] >= 1.0 ? FlowRole::wet : reached ? FlowRole::filling : FlowRole::dry);
  }
  for (size_t r = 0; r < vertices_; ++r)
    if (fixed_vertex[r] >= 0 && size_t(find(int32_t(r))) == r)
      s.exchanged[size_t(fixed_vertex[r])] -= mass[r];
  finish_step(in, s);
  return "";
}

}  // namespace rift
