#pragma once
// Integration rules on the joint's mid-surface triangle (femdem.md 1b, Lei's Yfd3JOINTSL):
//   3 points: barycentric (2/3, 1/6, 1/6) and permutations, weights 1/3; exact for quadratics.
//             The joint breaks when all 3 points have failed.
//   7 points: Dunavant degree 5 (the Y default), exact for quintics: the centroid, w = 9/40;
//             (b1, a1, a1) and permutations, a1 = (6 - sqrt 15)/21 = 0.1013, b1 = (9 + 2 sqrt 15)/21 =
//             0.7974, w = (155 - sqrt 15)/1200 = 0.1259; (b2, a2, a2) and permutations, a2 = (6 + sqrt 15)/21
//             = 0.4701, b2 = (9 - 2 sqrt 15)/21 = 0.0597, w = (155 + sqrt 15)/1200 = 0.1324 (femdem.md 1b
//             lists the same numbers to 10 digits). The joint breaks when at least 5 of the 7 points have
//             failed.
// Weights sum to 1 (they multiply the triangle's area). N[q] = (N0, N1, N2): the shape functions of
// corners 0, 1, 2 at point q, i.e. its barycentric coordinates.
#include <array>

namespace rift::kernels {

inline constexpr int kMaxJointPoints = 7;

struct JointRule {
  int points;      // 3 or 7
  int fail_count;  // the joint breaks when at least this many points have failed (3 or 5)
  std::array<std::array<double, 3>, kMaxJointPoints> N;
  std::array<double, kMaxJointPoints> w;
};

// The rule with `points` = 3 or 7 points (static storage). Any other count throws std::invalid_argument:
// a programming error, the scene reader validates the user's choice.
const JointRule& joint_rule(int points);

}  // namespace rift::kernels
