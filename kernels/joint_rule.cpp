#include "kernels/joint_rule.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rift::kernels {

namespace {

JointRule three_point() {
  JointRule r{};
  r.points = 3;
  r.fail_count = 3;
  const double big = 2.0 / 3.0, small = 1.0 / 6.0;
  r.N[0] = {big, small, small};
  r.N[1] = {small, big, small};
  r.N[2] = {small, small, big};
  r.w[0] = r.w[1] = r.w[2] = 1.0 / 3.0;
  return r;
}

// Dunavant (1985) degree 5 from its closed form, so every digit is the rule's own.
JointRule seven_point() {
  JointRule r{};
  r.points = 7;
  r.fail_count = 5;
  const double s15 = std::sqrt(15.0);
  const double a1 = (6.0 - s15) / 21.0, b1 = (9.0 + 2.0 * s15) / 21.0;  // near the corners
  const double a2 = (6.0 + s15) / 21.0, b2 = (9.0 - 2.0 * s15) / 21.0;  // near the edge midpoints
  const double w1 = (155.0 - s15) / 1200.0, w2 = (155.0 + s15) / 1200.0;
  r.N[0] = {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
  r.w[0] = 9.0 / 40.0;
  r.N[1] = {b1, a1, a1};
  r.N[2] = {a1, b1, a1};
  r.N[3] = {a1, a1, b1};
  r.N[4] = {b2, a2, a2};
  r.N[5] = {a2, b2, a2};
  r.N[6] = {a2, a2, b2};
  for (int q = 1; q <= 3; ++q) r.w[q] = w1;
  for (int q = 4; q <= 6; ++q) r.w[q] = w2;
  return r;
}

}  // namespace

const JointRule& joint_rule(int points) {
  static const JointRule three = three_point();
  static const JointRule seven = seven_point();
  if (points == 3) return three;
  if (points == 7) return seven;
  throw std::invalid_argument("joint_rule: integration points must be 3 or 7, got " + std::to_string(points));
}

}  // namespace rift::kernels
