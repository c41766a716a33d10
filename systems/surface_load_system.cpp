#include "systems/surface_load_system.hpp"

#include "engine/schedule/parallel.hpp"
#include "kernels/node_rows.hpp"
#include "systems/node_force_route.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

SurfaceLoadSystem::SurfaceLoadSystem(Store& store, std::vector<SolidBoundarySpec> loads,
                                     std::array<double, 6> initial_stress, size_t crack_face_begin)
    : store_(store),
      specs_(std::move(loads)),
      initial_stress_(initial_stress),
      values_(specs_.size()),
      crack_face_begin_(crack_face_begin),
      has_crack_faces_(crack_face_begin < store.table(solid::face_table).size()) {}

// The fracture log lists every broken joint once (initial cracks first), so it is the list of pressed
// joints; being part of the checkpoint, it needs no copy here.
size_t SurfaceLoadSystem::pressed_crack_faces() const {
  return has_crack_faces_ ? 2 * store_.table(solid::event_table).size() : 0;
}

Access SurfaceLoadSystem::access() const {
  using solid::col;
  std::vector<std::string> reads{solid::node::x.key(), solid::face::nodes.key(), solid::face::load.key()};
  // Reading the log orders this system before the joints' pass that appends to it: a joint broken in
  // step n is pressed from step n + 1 on, on any thread count.
  if (has_crack_faces_) reads.push_back(solid::event::joint.key());
  if (solid::face::fluid_pressure.exists(store_)) reads.push_back(solid::face::fluid_pressure.key());
  std::vector<std::string> writes{solid::face::corner_force.key()};
  if (has_crack_faces_) writes.push_back(col(solid::node_table, node_force_column(NodeForceSource::crack)));
  return {reads, writes};
}

void SurfaceLoadSystem::run(const StepContext& ctx) {
  // Loads act at the start of the step: the central-difference force is evaluated at time t.
  for (size_t i = 0; i < specs_.size(); ++i) {
    const SolidBoundarySpec& s = specs_[i];
    const double scale = s.function(ctx.time);
    kernels::FaceLoad& L = values_[i];
    L = {};
    if (s.kind == SolidBoundarySpec::Kind::fluid_pressure)
      continue;  // the face's own value, solid_load_face.fluid_pressure (written by the coupling)
    if (s.kind == SolidBoundarySpec::Kind::pressure)
      L.pressure = scale;
    else if (s.kind == SolidBoundarySpec::Kind::in_situ)
      for (int c = 0; c < 6; ++c) L.stress[c] = initial_stress_[c] * scale;
    else
      for (int c = 0; c < 3; ++c) L.traction[c] = s.direction[c] * scale;
  }
  Table& faces = store_.table(solid::face_table);
  const auto x = solid::node::x.in(store_);
  const auto nodes = solid::face::nodes.in(faces);
  const auto load = solid::face::load.in(faces);
  const auto force = solid::face::corner_force.in(faces);
  const std::span<const double> wetted = solid::face::fluid_pressure.exists(store_)
                                             ? solid::face::fluid_pressure.in(faces)
                                             : std::span<double>{};
  parallel_for(crack_face_begin_, 2048, [&](size_t begin, size_t end) {
    kernels::surface_loads(x, nodes, load, values_, force, begin, end, wetted);
  });
  if (!has_crack_faces_) return;
  // Each broken joint's two faces are adjacent rows; every row is written by one joint only.
  const auto broken = solid::event::joint.read(store_);
  parallel_for(broken.size(), 1024, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const size_t f = crack_face_begin_ + 2 * static_cast<size_t>(broken[k]);
      kernels::surface_loads(x, nodes, load, values_, force, f, f + 2);
    }
  });
  // Gathered per node in the log's order, serially: a node may sit on three pressed faces, and the order of
  // the sum must not depend on the threads. The pressed set only grows, so clearing its nodes first leaves
  // every other node at zero. Cost: 18 values per broken joint.
  auto node_force = store_.table(solid::node_table).span<double>(node_force_column(NodeForceSource::crack));
  // Corner k is corner k % 3 of face k / 3 of the pressed faces, two per broken joint.
  const auto face_of = [&](size_t k) {
    return crack_face_begin_ + 2 * static_cast<size_t>(broken[k / 6]) + (k / 3) % 2;
  };
  const auto node_of = [&](size_t k) { return nodes[3 * face_of(k) + k % 3]; };
  for (size_t k = 0; k < 6 * broken.size(); ++k)
    for (int c = 0; c < 3; ++c) node_force[3 * static_cast<size_t>(node_of(k)) + c] = 0.0;
  kernels::add_corners_to_nodes<3>(
      6 * broken.size(), node_of, [&](size_t k) { return &force[9 * face_of(k) + 3 * (k % 3)]; }, 1.0,
      node_force);
}

}  // namespace rift
