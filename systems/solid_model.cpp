#include "systems/solid_model.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <sstream>

#include "engine/core/error.hpp"
#include "kernels/reproducible_sum.hpp"
#include "systems/solid_partition_work.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

SolidModel::SolidModel(Store& store, const TetMesh& mesh, const SolidSpec& spec)
    : store_(store), spec_(spec) {
  if (spec_.initial_stress) initial_stress_ = spec_.initial_stress->tensor();
  zone_ = fracture_zone(mesh);
  for (uint8_t z : zone_) zone_tets_ += z;
  const DiscontinuousMesh dm = make_discontinuous(mesh, [&](size_t e) { return zone_[e] != 0; });
  build_nodes_and_tets(dm, mesh);
  assign_materials(mesh);
  apply_initial_velocity(mesh);
  apply_boundaries(dm, mesh);
  if (spec_.fracture) build_joints(dm);
  crack_face_begin_ = store_.table(solid::face_table).size();
  if (spec_.fracture && spec_.fracture->crack_pressure) add_crack_faces();
  build_force_slots();
  compute_mass_and_stable_dt();
  create_bookkeeping_tables();
  if (spec_.fracture) apply_initial_cracks(zone_);
  if (spec_.contact) build_contact(mesh);
  solid::energy::kinetic0.in(store_)[0] = energies().kinetic;

  std::vector<double> prestress;
  if (spec_.initial_stress)
    for (size_t m = 0; m < spec_.materials.size(); ++m)
      prestress.insert(prestress.end(), initial_stress_.begin(), initial_stress_.end());
  loads_ = std::make_unique<SurfaceLoadSystem>(store_, load_conditions_, initial_stress_, crack_face_begin_);
  tet_forces_ = std::make_unique<TetForceSystem>(store_, tet_materials_, std::move(prestress));
  // The tets' stress is written by the force pass; before the first step (the output at t = 0) the mesh
  // is undeformed, so it is the in-situ stress exactly.
  if (spec_.initial_stress) {
    auto stress = solid::tet::stress.in(store_);
    for (size_t e = 0; 6 * e < stress.size(); ++e)
      for (int c = 0; c < 6; ++c) stress[6 * e + c] = initial_stress_[c];
  }
  integration_ = std::make_unique<NodeIntegrationSystem>(store_, velocity_conditions_, spec_.gravity,
                                                         spec_.mass_damping);
  if (spec_.fracture && spec_.fracture->crack_pressure) integration_->gather(NodeForceSource::crack);
  if (contact_) integration_->gather(NodeForceSource::contact);
  if (spec_.fused_tet_pass) fused_tets_ = integration_->fuse_tet_forces(*tet_forces_);
  stable_dt_ = tet_stable_dt_;
  joint_stable_dt_ = INFINITY;
  if (spec_.fracture) {
    const kernels::Softening rule =
        spec_.fracture->y_compatible ? kernels::Softening::y_compatible : kernels::Softening::energy_exact;
    joint_forces_ = std::make_unique<JointForceSystem>(store_, joint_materials_,
                                                       spec_.fracture->integration_points, rule);
    // Evaluate the joints once in the initial configuration: their stored energy there (the in-situ
    // state) is the zero of the energy balance.
    joint_forces_->run(StepContext{0, 0.0, 0.0});
    solid::energy::joint_energy0.in(store_)[0] =
        kernels::reproducible_total(solid::joint::stored_energy.read(store_));
    Table& joints = store_.table(solid::joint_table);
    const Table& nodes = store_.table(solid::node_table);
    joint_stable_dt_ = kernels::joint_stable_step(
        solid::node::x0.read(nodes), solid::joint::nodes.read(joints), solid::joint::material.read(joints),
        joint_materials_, solid::node::mass.read(nodes), {}, 0, joints.size());
    // A tet corner sits in up to three joints besides its tet: Gershgorin adds their omega^2
    // (kernels/joint_forces.hpp), so 1/dt^2 = 1/dt_tet^2 + 3/dt_joint^2.
    stable_dt_ = 1.0 / std::sqrt(1.0 / (tet_stable_dt_ * tet_stable_dt_) +
                                 3.0 / (joint_stable_dt_ * joint_stable_dt_));
  }
  if (contact_) {
    // The contact springs act on face corners on top of the tets: their omega^2 adds. On a joint's face the
    // contact replaces the joint's spring once it breaks, so there the larger of the two counts; on the
    // outer faces of a mesh of several bodies the contact adds to everything.
    const double inv_t = 1.0 / (tet_stable_dt_ * tet_stable_dt_);
    const double inv_j = std::isfinite(joint_stable_dt_) ? 3.0 / (joint_stable_dt_ * joint_stable_dt_) : 0.0;
    const double dt_cj = contact_->joint_face_stable_step(), dt_co = contact_->outer_face_stable_step();
    stable_dt_ = contact_->damped_step(
        1.0 / std::sqrt(inv_t + std::max(inv_j, 1.0 / (dt_cj * dt_cj)) + 1.0 / (dt_co * dt_co)));
  } else if (spec_.fracture) {
    spdlog::warn(
        "solid: a fracture zone without solid.contact: the faces of broken joints will pass "
        "through each other; add a solid.contact section to make them touch");
  }
  if (spec_.mass_scaling_step > 0.0) scale_masses();
  const size_t joints = joint_count();
  spdlog::info(
      "solid: {} tets ({} in the fracture zone, {:.1f} %), {} nodes, {} joints, {} loaded faces",
      store_.table(solid::tet_table).size(), zone_tets_,
      100.0 * static_cast<double>(zone_tets_) / std::max<size_t>(1, store_.table(solid::tet_table).size()),
      store_.table(solid::node_table).size(), joints, crack_face_begin_);
  if (fused_tets_ > 0)
    spdlog::debug("solid: the node pass computes the forces of {} tets (solid.fused_tet_pass)", fused_tets_);
  spdlog::info(
      "solid: stable step {:.4g} s (tets {:.4g} s, set by tet {}; joints {:.4g} s; contact {:.4g} s)",
      stable_dt_, tet_stable_dt_, critical_tet_, joint_stable_dt_,
      contact_ ? contact_->stable_step() : INFINITY);
}

void SolidModel::accept_fluid_forces() {
  store_.table(solid::node_table).add<double>(route_entry(NodeForceSource::fluid).column, 3);
  integration_->gather(NodeForceSource::fluid);
}

void SolidModel::accept_crack_fluid_forces() {
  store_.table(solid::node_table).add<double>(route_entry(NodeForceSource::crack).column, 3);
  integration_->gather(NodeForceSource::crack);
}

void SolidModel::add_node_mass(std::span<const double> extra) {
  Table& nodes = store_.table(solid::node_table);
  auto mass = solid::node::mass.in(nodes);
  auto inv_mass = solid::node::inv_mass.in(nodes);
  for (size_t n = 0; n < nodes.size(); ++n) {
    mass[n] += extra[n];
    inv_mass[n] = mass[n] > 0 ? 1.0 / mass[n] : 0.0;
  }
  solid::energy::kinetic0.in(store_)[0] = energies().kinetic;
}

size_t SolidModel::joint_count() const {
  return store_.has(solid::joint_table) ? store_.table(solid::joint_table).size() : 0;
}

size_t SolidModel::broken_joint_count() const {
  return store_.table(solid::event_table).size();
}

std::optional<std::string> SolidModel::check_health(const StepContext& after) {
  std::ostringstream why;
  if (tet_forces_->inverted() > 0) {
    const int64_t e = tet_forces_->first_inverted();
    const auto conn = solid::tet::nodes.read(store_);
    const auto x = solid::node::x.read(store_);
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) c[i] += 0.25 * x[3 * conn[4 * e + k] + i];
    why << tet_forces_->inverted() << " tetrahedra inverted (J <= 0) at step " << after.step
        << ", t = " << after.time << " s; first: tet " << e << " at (" << c[0] << ", " << c[1] << ", " << c[2]
        << ") m. Likely cause: a load too large or too sudden for the element (or a dt above the stable "
           "step). What to change: lower the load or its rate, refine the mesh there, or reduce time.dt / "
           "time.safety.";
    return why.str();
  }
  if (integration_->non_finite_nodes() > 0) {
    why << integration_->non_finite_nodes() << " solid nodes have a non-finite position or velocity at step "
        << after.step << ", t = " << after.time << " s. Likely cause: dt above the stable step ("
        << stable_dt_ << " s; tets " << tet_stable_dt_ << " s, set by tet " << critical_tet_ << "; joints "
        << joint_stable_dt_
        << " s) or a load that grows without bound. What to change: reduce time.dt or time.safety, check "
           "loads and materials.";
    return why.str();
  }
  // The energy sums cost a serial pass over nodes, tets and joints (under 1 % of a step when done every
  // 16 steps): often enough to stop a blow-up, which grows by a constant factor per step (1.6 per step
  // at 2 x the estimate on the wave bar), before it inverts tets or reaches infinity; and after the last
  // step, so that a run that went unstable near its end does not finish as if it were fine.
  if ((!share_ || split_) && (after.step % kObservedEvery == 0 || after.last)) return check_energy(after);
  return std::nullopt;
}

// Energy that appears without work to feed it: the balance error exceeds 10 % of the largest energy
// scale seen so far, plus a floor (the strain energy of a 1e-6 strain in the whole body, sum E V0 *
// 1e-12) below which an error is round-off in a body at rest, not physics. A stable run keeps it at the level
// of the time discretisation (docs/validation.md).
std::optional<std::string> SolidModel::check_energy(const StepContext& after) {
  const SolidEnergies e = energies();
  const double scale = std::abs(e.external_work) + e.kinetic + std::abs(e.elastic) +
                       std::abs(e.joint_stored) + e.damping + std::abs(e.fracture) + e.break_release +
                       e.contact_stored + e.friction + e.contact_damping;
  largest_energy_ = std::max(largest_energy_, scale);
  const double error = e.balance_error();
  const double tolerance = 0.1 * largest_energy_ + energy_floor_;
  if (e.contact_stored < -tolerance) {
    std::ostringstream why;
    why << "contact is putting energy into the solid at step " << after.step << ", t = " << after.time
        << " s: the contact forces did " << -(e.contact_stored + e.friction + e.contact_damping)
        << " J of net work on it against a largest energy of " << largest_energy_
        << " J. Likely cause: the contact penalty is too stiff for the step (contact stable step "
        << contact_->stable_step() << " s) or bodies hit too fast for it. What to change: reduce time.dt or "
        << "time.safety, or lower solid.contact.penalty.";
    return why.str();
  }
  // The balance closes, but the joints' books (the work done on them less what they store: what fracture
  // took, >= 0 but for the small loops of the law's compression-shear coupling, kernels/joint_law.hpp) are
  // far below zero: the joints hand out energy nobody put in. A step-driven blow-up fails the balance first
  // and gets that diagnosis (below).
  if (std::isfinite(error) && std::abs(error) <= tolerance) {
    if (e.fracture >= -tolerance) return std::nullopt;
    std::ostringstream why;
    why << "the joints are putting energy into the solid at step " << after.step << ", t = " << after.time
        << " s: they gave back " << -e.fracture << " J more than the work done on them, against a largest "
        << "energy of " << largest_energy_ << " J";
    const Table& events = store_.table(solid::event_table);
    if (events.size() > 0) {
      const auto c = solid::event::centroid.read(events);
      const size_t last = events.size() - 1;
      why << "; " << events.size() << " joints broken, the last at (" << c[3 * last] << ", "
          << c[3 * last + 1] << ", " << c[3 * last + 2] << ") m";
    }
    why << ". Likely cause: joints cycling in shear under compression, where the Mohr-Coulomb joint law "
        << "is not conservative (a zone of small tets breaking up), or a joint penalty too stiff for the "
        << "step (joints " << joint_stable_dt_ << " s). What to change: reduce time.dt or time.safety, "
        << "lower the joint penalty, or mesh that zone with fewer small or flat tets.";
    return why.str();
  }
  std::ostringstream why;
  why << "energy is not conserved at step " << after.step << ", t = " << after.time << " s: external work "
      << e.external_work << " J, but kinetic " << e.kinetic << " + elastic " << e.elastic << " + joints "
      << e.joint_stored << " + damping " << e.damping << " + fracture " << e.fracture
      << " + released at breaks " << e.break_release << " + contact "
      << e.contact_stored + e.friction + e.contact_damping << " J (error " << error
      << " J). Energy growing without work to feed it is a numerical instability. "
      << "Likely cause: a step above the stable one (" << stable_dt_
      << " s) or a joint or contact penalty too stiff for the step. What to change: reduce time.dt or "
         "time.safety, or lower the joint (or contact) penalty.";
  return why.str();
}

void SolidModel::partition_work(std::vector<PartitionWork>& domains) const {
  const auto tets = solid::tet::nodes.read(store_), vertex = solid::node::vertex.read(store_);
  if (spec_.fracture)
    domains.push_back(solid_partition_work(tets, vertex, solid::joint::nodes.read(store_),
                                           solid::joint::tets.read(store_)));
  else
    domains.push_back(solid_partition_work(tets, vertex, {}, {}));
  domains.back().node_units = integration_->sum_units();  // the node pass's energy sums keep units whole
}

void SolidModel::compute_only(const RankHalo& share) {
  if (contact_)
    throw Error("solid: a split run does not yet split contact pairs; run this scene on one process");
  if (share.elements.empty()) throw Error("solid: a share names no tets");
  tet_forces_->compute_only(share.elements[0]);
  if (joint_forces_) {
    if (share.elements.size() < 2) throw Error("solid: a share of a fractured solid names no joints");
    joint_forces_->compute_only(share.elements[1]);
  }
  integration_->compute_only(share.owned);
  share_ = true;
}

void SolidModel::summarize(nlohmann::json& summary) const {
  auto& s = summary["solid"];
  s["nodes"] = store_.table(solid::node_table).size();
  s["tets"] = store_.table(solid::tet_table).size();
  s["zone_tets"] = zone_tets_;
  s["joints"] = joint_count();
  s["broken_joints"] = broken_joint_count();
  s["loaded_faces"] = crack_face_begin_;
  s["crack_faces_pressed"] = loads_->pressed_crack_faces();
  s["mass_damping"] = spec_.mass_damping(0.0);  // at the start; a schedule is in the resolved scene
  s["stable_dt"] = stable_dt_;
  s["tet_stable_dt"] = tet_stable_dt_;
  s["joint_stable_dt"] = joint_stable_dt_;  // infinite without joints (the file says "inf")
  s["critical_tet"] = critical_tet_;
  if (spec_.mass_scaling_step > 0.0)
    s["mass_scaling"] = {{"step", spec_.mass_scaling_step},
                         {"scaled_nodes", mass_scaling_.scaled_nodes},
                         {"added_mass", mass_scaling_.added},
                         {"added_fraction", mass_scaling_.added / mass0_},
                         {"largest_factor", mass_scaling_.largest_factor}};
  const SolidEnergies e = energies();
  s["energy"] = {{"kinetic", e.kinetic},
                 {"elastic", e.elastic},
                 {"joint_stored", e.joint_stored},
                 {"damping", e.damping},
                 {"fracture", e.fracture},
                 {"break_release", e.break_release},
                 {"contact_stored", e.contact_stored},
                 {"friction", e.friction},
                 {"contact_damping", e.contact_damping},
                 {"external_work", e.external_work},
                 {"balance_error", e.balance_error()}};
  size_t count[4] = {0, 0, 0, 0};
  for (uint8_t m : solid::event::mode.read(store_)) ++count[m & 3];
  s["fractures"] = {{"tensile", count[1]}, {"shear", count[2]}, {"initial", count[3]}};
  if (contact_) {
    const ContactTotals c = contact_->totals();
    s["contact"] = {{"bodies", contact_->bodies()},
                    {"candidates", c.candidates},
                    {"pairs", c.pairs},
                    {"touching", c.touching},
                    {"detections", c.detections},
                    {"penalty", contact_->law().penalty},
                    {"buffer", contact_->buffer()},
                    {"stable_dt", contact_->stable_step()},
                    {"damping_time", contact_->damping_time()}};
  }
}

}  // namespace rift
