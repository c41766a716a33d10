#pragma once
// Distance from a point to a set of triangles (a CGAL AABB tree over them): the sizing field of an
// adaptive mesh refined towards a surface (graded_box.hpp). Exact up to round-off; a query costs
// O(log n) box tests. Queries from one thread at a time (Mesh_3 runs sequentially). An empty set is
// infinitely far away.
#include <memory>
#include <span>

#include "engine/core/vec3.hpp"

namespace rift {

class SurfaceDistance {
 public:
  // triangles: 9 values (3 corners, xyz) per triangle; copied. Degenerate triangles are skipped.
  explicit SurfaceDistance(std::span<const double> triangles);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;

  double operator()(const Vec3& p) const;
  size_t triangle_count() const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace rift
