#pragma once
// The faces of a tet and a key for matching them between tets: shared by the FEMDEM mesh builder
// (discontinuous_mesh.cpp) and the mesh conversion (mesh_conversion.cpp).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

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

// The faces of a single tet (the boundary), each as (tet, face).
using OpenFaces = std::unordered_map<FaceKey, std::pair<int32_t, int32_t>, FaceKeyHash>;

// Calls shared(a, face_a, b, face_b) for every face that two tets share (a < b, faces as in
// kTetFaceCorners), in the order in which the second tet meets it: the first tet to show a face waits in a
// map for the second. Returns the faces left waiting: the boundary's.
template <class Shared>
OpenFaces for_each_shared_face(std::span<const std::array<int32_t, 4>> tets, Shared&& shared) {
  OpenFaces open;
  open.reserve(2 * tets.size());
  for (size_t e = 0; e < tets.size(); ++e)
    for (int32_t f = 0; f < 4; ++f) {
      std::array<int32_t, 3> v;
      for (int i = 0; i < 3; ++i) v[size_t(i)] = tets[e][size_t(kTetFaceCorners[f][i])];
      const auto [it, inserted] = open.try_emplace(face_key(v), int32_t(e), f);
      if (inserted) continue;
      const auto [a, fa] = it->second;
      open.erase(it);
      shared(a, fa, int32_t(e), f);
    }
  return open;
}

}  // namespace rift
