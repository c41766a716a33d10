// Selective mass scaling (solid.mass_scaling_step): the explicit step of a mesh is set by its smallest,
// stiffest corners (in the wedge scene, the 0.17 mm tets where the notch tapers to its tip: 1 % of the nodes
// allow less than half the step of the others). Making those few nodes heavier lifts the step for all; the
// price is inertia that is not there, near where it sits. docs/speed-accuracy.md measures that price.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "kernels/joint_forces.hpp"
#include "systems/solid_model.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

void SolidModel::scale_masses() {
  Table& nodes = store_.table(solid::node_table);
  const Table& tets = store_.table(solid::tet_table);
  const auto x0 = solid::node::x0.read(nodes);
  auto mass = solid::node::mass.in(nodes);
  auto inv_mass = solid::node::inv_mass.in(nodes);

  // Per node, the row sums of the Gershgorin bound (kernels/stable_step.hpp): its tet, its joints, and the
  // contact springs, which on a joint's face replace the joint's once it breaks (the larger of the two
  // counts, as in the global step) and on outer faces add. omega_n^2 = K_n / m_n.
  std::vector<double> stiffness(nodes.size(), 0.0), tet_mass(tets.size());
  const auto volume = solid::tet::volume0.read(tets);
  const auto material = solid::tet::material.read(tets);
  for (size_t e = 0; e < tets.size(); ++e)
    tet_mass[e] = spec_.materials[static_cast<size_t>(material[e])].density * volume[e];
  kernels::add_tet_node_stiffness(solid::tet::nodes.read(tets), tet_steps_, tet_mass, stiffness);
  std::vector<double> joint(nodes.size(), 0.0);
  if (joint_forces_) {
    const Table& joints = store_.table(solid::joint_table);
    kernels::add_joint_node_stiffness(x0, solid::joint::nodes.read(joints),
                                      solid::joint::material.read(joints), joint_materials_,
                                      solid::joint::broken.read(joints), joint);
  }
  std::vector<double> contact_joint, contact_outer;
  if (contact_) contact_->node_stiffness(contact_joint, contact_outer);
  for (size_t n = 0; n < nodes.size(); ++n) {
    const double on_joint_faces = contact_ ? std::max(joint[n], 2.0 * contact_joint[n]) : joint[n];
    stiffness[n] += on_joint_faces + (contact_ ? 2.0 * contact_outer[n] : 0.0);
  }

  mass0_ = 0.0;
  for (double m : mass) mass0_ += m;
  const double before = kernels::node_stable_step(stiffness, mass);
  mass_scaling_ = kernels::scale_masses_to_step(stiffness, spec_.mass_scaling_step, mass, inv_mass);
  stable_dt_ = kernels::node_stable_step(stiffness, mass);
  if (contact_) {
    contact_->update_stable_step();
    stable_dt_ = contact_->damped_step(stable_dt_);
  }
  solid::energy::kinetic0.in(store_)[0] = energies().kinetic;

  const double fraction = mass_scaling_.added / mass0_;
  std::string where;
  if (mass_scaling_.largest_node >= 0) {
    const size_t n = static_cast<size_t>(mass_scaling_.largest_node);
    where = fmt::format(", up to {:.3g} x at node {} ({:.4g}, {:.4g}, {:.4g}) m",
                        mass_scaling_.largest_factor, n, x0[3 * n], x0[3 * n + 1], x0[3 * n + 2]);
  }
  spdlog::info(
      "solid: mass scaling to a step of {:.4g} s (per-node step before {:.4g} s): {} of {} nodes heavier "
      "({:.2f} %), +{:.4g} kg = {:.3g} % of the mass{}",
      spec_.mass_scaling_step, before, mass_scaling_.scaled_nodes, nodes.size(),
      100.0 * static_cast<double>(mass_scaling_.scaled_nodes) / static_cast<double>(nodes.size()),
      mass_scaling_.added, 100.0 * fraction, where);
  if (fraction > 0.01)
    spdlog::warn(
        "solid: mass scaling added {:.3g} % of the solid's mass (more than 1 %): inertia that is not there "
        "changes the dynamics; lower solid.mass_scaling_step or check the result against a run without it",
        100.0 * fraction);
}

}  // namespace rift
