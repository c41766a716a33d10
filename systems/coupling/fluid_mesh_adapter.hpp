#pragma once
// The adaptive fluid mesh's maker (fluid.adapt, docs/fluid.md "Adaptive mesh"): the box of
// fluid.mesh.generate meshed with size_min at the solid's current surface (the continuous surface of the
// mesh conversion: outer faces, notches and both faces of every broken joint, as fluid.adapt.surfaces
// selects, at the solid's node positions now), growing by `grading` per unit distance up to size_max. The
// same solid state and scene give the same mesh, bit for bit (graded_box.hpp), so a restart can rely on the
// checkpoint's mesh.
#include <cstdint>

#include "engine/core/table.hpp"
#include "engine/mesh/graded_box.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

class MeshConversionModel;

class FluidMeshAdapter {
 public:
  FluidMeshAdapter(const Store& store, MeshConversionModel& conversion, const MeshGenerateSpec& box,
                   const FluidAdaptSpec& spec);

  // A mesh of the box around the solid as the store holds it now, ordered along a space-filling curve.
  TetMesh make();
  int64_t interval() const { return interval_; }
  // Whether the fluid step that ends window `window` (1, 2, ...) is followed by a remesh.
  bool due_after(int64_t window) const { return interval_ > 0 && window % interval_ == 0; }
  double seconds() const { return seconds_; }  // wall time in make(), summed
  int64_t calls() const { return calls_; }

 private:
  const Store& store_;
  MeshConversionModel& conversion_;
  GradedBoxSpec box_;
  int64_t interval_;
  bool tags_[3];  // per SurfaceTag: refine at it
  double seconds_ = 0.0;
  int64_t calls_ = 0;
};

}  // namespace rift
