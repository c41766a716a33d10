#include "engine/mesh/surface_distance.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rift {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = K::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
}  // namespace

struct SurfaceDistance::Tree {
  std::vector<Triangle> triangles;  // the tree's primitives point into this
  rift::Tree tree;
};

SurfaceDistance::SurfaceDistance(std::span<const double> t) : tree_(std::make_unique<Tree>()) {
  const size_t n = t.size() / 9;
  tree_->triangles.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const double* c = &t[9 * i];
    Triangle tri(K::Point_3(c[0], c[1], c[2]), K::Point_3(c[3], c[4], c[5]), K::Point_3(c[6], c[7], c[8]));
    if (!tri.is_degenerate()) tree_->triangles.push_back(tri);
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  if (!tree_->triangles.empty()) tree_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

double SurfaceDistance::operator()(const Vec3& p) const {
  if (tree_->triangles.empty()) return std::numeric_limits<double>::infinity();
  return std::sqrt(tree_->tree.squared_distance(K::Point_3(p[0], p[1], p[2])));
}

size_t SurfaceDistance::triangle_count() const {
  return tree_->triangles.size();
}

}  // namespace rift
