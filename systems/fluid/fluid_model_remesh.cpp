// The adaptive fluid mesh (FluidSpec::adapt, docs/fluid.md "Adaptive mesh"): a new mesh replaces the
// solver's, the fields carried over by P1 interpolation, and a restart finds the mesh in the store.
#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/fluid_solid_exchange.hpp"
#include "kernels/volume_fraction.hpp"
#include "systems/fluid/fluid_model.hpp"
#include "systems/fluid/fluid_tables.hpp"

namespace rift {

namespace {

std::vector<double> flat_nodes(const TetMesh& mesh) {
  std::vector<double> x;
  x.reserve(3 * mesh.nodes.size());
  for (const auto& p : mesh.nodes) x.insert(x.end(), p.begin(), p.end());
  return x;
}

// P1 interpolation of `field` (`components` per node of the old mesh) at `points`. Every point must lie in
// the old mesh (both meshes fill the same box; 1e-9 in barycentric terms absorbs round-off on its faces).
std::vector<double> interpolate(std::span<const double> old_x, std::span<const int32_t> old_tets,
                                std::span<const double> field, size_t components,
                                std::span<const double> points,
                                std::span<const kernels::CouplingPair> candidates) {
  const size_t n_old = old_x.size() / 3, n_new = points.size() / 3;
  std::vector<double> one(n_old), out_one(n_new), out(components * n_new);
  for (size_t c = 0; c < components; ++c) {
    for (size_t i = 0; i < n_old; ++i) one[i] = field[components * i + c];
    const size_t outside =
        kernels::interpolate_p1_at_points(old_x, old_tets, one, points, candidates, out_one);
    if (outside > 0)
      throw Error(
          fmt::format("fluid remesh: {} nodes of the new mesh lie outside the old one (both should fill "
                      "the box of fluid.mesh.generate); an internal error, please report the scene",
                      outside));
    for (size_t i = 0; i < n_new; ++i) out[components * i + c] = out_one[i];
  }
  return out;
}

}  // namespace

// The store's mesh tables from `mesh` (every column zeroed first: the coupling refills its own), and the
// per-cell geometry of the outputs.
void FluidModel::store_mesh(const TetMesh& mesh) {
  const size_t nn = mesh.nodes.size(), nt = mesh.tets.size();
  Table& nodes = store_.table(fluid::node_table);
  Table& tets = store_.table(fluid::tet_table);
  nodes.resize(0);
  nodes.resize(nn);
  tets.resize(0);
  tets.resize(nt);
  const auto x = flat_nodes(mesh);
  std::copy(x.begin(), x.end(), fluid::node::x.in(nodes).begin());
  auto conn = fluid::tet::nodes.in(tets);
  for (size_t t = 0; t < nt; ++t) std::copy(mesh.tets[t].begin(), mesh.tets[t].end(), &conn[4 * t]);
  if (spec_.adapt) {
    Table& faces = store_.table(fluid::boundary_table);
    faces.resize(mesh.triangles.size());
    auto fn = fluid::boundary::nodes.in(faces);
    auto fs = fluid::boundary::surface.in(faces);
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      std::copy(mesh.triangles[f].begin(), mesh.triangles[f].end(), &fn[3 * f]);
      fs[f] = mesh.triangle_surface[f];
    }
  }
}

// The mesh as the store holds it (the last remesh's, or the checkpoint's on a restart).
TetMesh FluidModel::mesh_from_store() const {
  TetMesh mesh;
  const Table& nodes = store_.table(fluid::node_table);
  const Table& tets = store_.table(fluid::tet_table);
  const Table& faces = store_.table(fluid::boundary_table);
  const auto x = fluid::node::x.in(nodes);
  const auto conn = fluid::tet::nodes.in(tets);
  const auto fn = fluid::boundary::nodes.read(faces);
  const auto fs = fluid::boundary::surface.read(faces);
  mesh.nodes.resize(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) mesh.nodes[n] = {x[3 * n], x[3 * n + 1], x[3 * n + 2]};
  mesh.tets.resize(tets.size());
  for (size_t t = 0; t < tets.size(); ++t)
    mesh.tets[t] = {conn[4 * t], conn[4 * t + 1], conn[4 * t + 2], conn[4 * t + 3]};
  mesh.tet_region.assign(tets.size(), 0);
  mesh.region_names = {"domain"};
  mesh.triangles.resize(faces.size());
  mesh.triangle_surface.resize(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    mesh.triangles[f] = {fn[3 * f], fn[3 * f + 1], fn[3 * f + 2]};
    mesh.triangle_surface[f] = fs[f];
  }
  mesh.surface_names = surface_names_;
  return mesh;
}

void FluidModel::remesh(const TetMesh& mesh, double time) {
  // The old mesh and state, from the store (what the last step committed).
  const Table& nodes = store_.table(fluid::node_table);
  const Table& tets = store_.table(fluid::tet_table);
  const std::vector<double> old_x(fluid::node::x.in(nodes).begin(), fluid::node::x.in(nodes).end());
  const std::vector<int32_t> old_tets(fluid::tet::nodes.in(tets).begin(), fluid::tet::nodes.in(tets).end());
  const bool previous = fluid::step::has_previous.read(store_)[0] != 0;
  // Candidate old tets of each new node: zero-size boxes against the old tets' boxes.
  const std::vector<double> points = flat_nodes(mesh);
  const size_t nt_old = old_tets.size() / 4;
  std::vector<int32_t> ids(nt_old);
  for (size_t t = 0; t < nt_old; ++t) ids[t] = static_cast<int32_t>(t);
  std::vector<double> lo(3 * nt_old), hi(3 * nt_old);
  kernels::tet_bounding_boxes(old_x, old_tets, ids, lo, hi, 0, nt_old);
  // The boxes grow by round-off (1e-9 of the domain's extent): a new node on a face of the domain may
  // lie a few ulps outside the old tets' boxes.
  double span = 0.0;
  for (int d = 0; d < 3; ++d) {
    double a = lo[d], b = hi[d];
    for (size_t t = 0; t < nt_old; ++t) a = std::min(a, lo[3 * t + d]), b = std::max(b, hi[3 * t + d]);
    span = std::max(span, b - a);
  }
  kernels::CouplingBroadPhaseWorkspace ws;
  kernels::coupling_broad_phase({points, points, lo, hi, 1e-9 * span}, ws);
  const auto u = interpolate(old_x, old_tets, fluid::node::velocity.in(nodes), 3, points, ws.pairs);
  const auto p = interpolate(old_x, old_tets, fluid::node::pressure.in(nodes), 1, points, ws.pairs);
  const auto u_old =
      previous ? interpolate(old_x, old_tets, fluid::node::previous_velocity.in(nodes), 3, points, ws.pairs)
               : std::vector<double>{};

  build_solver(mesh);
  store_mesh(mesh);
  use_store_state();
  // The fresh solver takes the carried-over state (the next step imposes the boundary values on Dirichlet
  // nodes); its pressure preconditioner is assembled at that step (coefficients 0: not assembled yet), and
  // the pressure subscale starts from zero on the new cells (store_mesh's fresh rows are zero).
  Table& out = store_.table(fluid::node_table);
  std::copy(u.begin(), u.end(), fluid::node::velocity.in(out).begin());
  std::copy(p.begin(), p.end(), fluid::node::pressure.in(out).begin());
  if (previous) std::copy(u_old.begin(), u_old.end(), fluid::node::previous_velocity.in(out).begin());
  solver_->restored(time);
  fluid::step::remeshes.in(store_)[0] += 1;
}

}  // namespace rift
