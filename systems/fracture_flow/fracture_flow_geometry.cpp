// The fracture flow's geometry each step (systems/fracture_flow/fracture_flow_system.hpp): the wet
// triangles from the nodes' positions, the vertices' volumes, the corner entries' pressure area vectors,
// the borehole wall's share, and the closure's compliance per vertex. Per-triangle and per-entry work
// runs in fixed blocks in parallel; every sum onto a vertex or an entry is a gather in triangle (or
// entry) order, so the results do not depend on the thread count.
#include <algorithm>

#include "engine/schedule/parallel.hpp"
#include "kernels/crack_pressure_closure.hpp"
#include "systems/fracture_flow/fracture_flow_system.hpp"
#include "systems/solid_tables.hpp"

namespace rift {

// The wet triangles' mid-surfaces from the nodes' current positions; the vertices' volumes (apertures
// floored), areas and positions; the corner entries' pressure area vectors.
void FractureFlowSystem::geometry() {
  const auto x = solid::node::x.read(store_);
  parallel_for(joints_.size(), kTriangleGrain, [&](size_t begin, size_t end) {
    constexpr size_t ahead = kPrefetchAhead / 4;  // six rows per triangle
    for (size_t t = begin; t < end; ++t) {
      if (t + ahead < end)
        for (size_t c = 0; c < 6; ++c)
          __builtin_prefetch(&x[3 * size_t(triangle_nodes_[6 * (t + ahead) + c])]);
      const double* corner[6];
      for (size_t c = 0; c < 6; ++c) corner[c] = &x[3 * size_t(triangle_nodes_[6 * t + c])];
      const kernels::CrackTriangle tri = kernels::crack_triangle(corner);
      area_[t] = tri.area;
      for (size_t d = 0; d < 3; ++d) normal_[3 * t + d] = tri.normal[d];
      for (size_t c = 0; c < 3; ++c) {
        opening_[3 * t + c] = tri.opening[c];
        aperture_[3 * t + c] = std::max(tri.opening[c], spec_.aperture_floor);
        for (size_t d = 0; d < 3; ++d) tri_x_[9 * t + 3 * c + d] = tri.mid[c][d];
      }
    }
  });
  // Each vertex from its triangles' corners, in triangle order.
  parallel_for(vertex_corners_.size(), kVertexGrain, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      double floor = 0.0, volume = 0.0, area = 0.0, weight = 0.0, mid[3] = {0.0, 0.0, 0.0};
      for (int32_t k : vertex_corners_.of(v)) {
        const size_t t = size_t(k) / 3;
        floor += area_[t] * spec_.aperture_floor / 3.0;
        volume += area_[t] * aperture_[size_t(k)] / 3.0;
        area += area_[t] / 3.0;
        weight += 1.0;
        for (size_t d = 0; d < 3; ++d) mid[d] += tri_x_[3 * size_t(k) + d];
      }
      floor_volume_[v] = floor;
      volume_[v] = volume;
      vertex_area_[v] = area;
      for (size_t d = 0; d < 3; ++d) vertex_x_[3 * v + d] = weight > 0.0 ? mid[d] / weight : 0.0;
    }
  });
  parallel_for(entry_corners_.size(), kEntryGrain, [&](size_t begin, size_t end) {
    kernels::gather_area_vectors(entry_corners_.start, entry_corners_.items, normal_, area_, opening_,
                                 spec_.aperture_floor, area_vector_, open_area_vector_, begin, end);
  });
  if (well_is_wall()) wall_geometry(x);
}

// The borehole's wall: its pressure area vectors join its nodes' entries (always open: the hole does
// not close), and the well's volume takes the hole's change from the reference positions, a . (x - x0)
// summed over the wall's nodes (to first order in the displacement). The well sits at the injection point.
// The wall nodes' reference positions come from wall_x0_, their copy in entry order: the step reads the
// solid's x0 column nowhere else, so gathering it per step missed the cache at every node.
void FractureFlowSystem::wall_geometry(std::span<const double> x) {
  wall_area_vector_.assign(3 * wall_entries_, 0.0);
  kernels::add_wall_area_vectors(wall_.face_nodes, wall_entry_, x, wall_area_vector_);
  double change = 0.0;  // a local sum: the member would be stored and reloaded at every term
  for (size_t e = 0; e < wall_entries_; ++e) {
    const size_t n = size_t(node_[e]);
    for (size_t d = 0; d < 3; ++d) {
      area_vector_[3 * e + d] += wall_area_vector_[3 * e + d];
      open_area_vector_[3 * e + d] += wall_area_vector_[3 * e + d];
      change += wall_area_vector_[3 * e + d] * (x[3 * n + d] - wall_x0_[3 * e + d]);
    }
  }
  hole_change_ = change;
  volume_[0] += hole_change_;
  floor_volume_[0] += hole_change_;  // the hole does not close like a crack: only the crack part is floored
  for (size_t d = 0; d < 3; ++d) vertex_x_[d] = spec_.point[d];
}

// C per vertex, with all its corners and with the open ones only (kernels/crack_pressure_closure.hpp), and
// the numerator of the pressure its predicted volume felt (applied_: the compliance-weighted sum of its
// entries' felt pressures): each entry's weights in parallel blocks, then gathered per vertex in entry
// order.
void FractureFlowSystem::closure_compliance(const kernels::CrackClosureNodes& closure,
                                            const kernels::CrackClosureNodes& open_closure, double scale) {
  entry_weight_.resize(3 * node_.size());
  parallel_for(node_.size(), kEntryGrain, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const double all = kernels::closure_weight(closure, i);
      entry_weight_[3 * i] = all;
      entry_weight_[3 * i + 1] = kernels::closure_weight(open_closure, i);
      entry_weight_[3 * i + 2] = all * felt_[i];
    }
  });
  parallel_for(vertex_entries_.size(), kVertexGrain, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      double all = 0.0, open = 0.0, felt = 0.0;
      for (int32_t i : vertex_entries_.of(v)) {
        all += scale * entry_weight_[3 * size_t(i)];
        open += scale * entry_weight_[3 * size_t(i) + 1];
        felt += scale * entry_weight_[3 * size_t(i) + 2];
      }
      compliance_[v] = all;
      compliance_open_[v] = open;
      applied_[v] = felt;
    }
  });
}

}  // namespace rift
