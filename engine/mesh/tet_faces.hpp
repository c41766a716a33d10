#pragma once
// The faces of a tet and a key for matching them between tets: shared by the FEMDEM mesh builder
// (discontinuous_mesh.cpp) and the mesh conversion (mesh_conversion.cpp).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace rift {

// Outward faces of a positively oriented tet, as corner indices; face k is opposite corner k.
inline constexpr int32_t kTetFaceCorners[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// A face as its sorted vertex triple, so both tets that share it give the same key.
struct FaceKey {
  std::array<int32_t, 3> v;
  bool operator==(const FaceKey& o) const { return v == o.v; }
};
struct FaceKeyHash {
  size_t operator()(const FaceKey& k) const {
    uint64_t h = 1469598103934665603ull;  // FNV-1a over the three ids
    for (int32_t x : k.v) h = (h ^ static_cast<uint32_t>(x)) * 1099511628211ull;
    return h;
  }
};
inline FaceKey face_key(std::array<int32_t, 3> v) {
  std::sort(v.begin(), v.end());
  return {v};
}

}  // namespace rift
