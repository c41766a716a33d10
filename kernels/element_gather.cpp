#include "kernels/element_gather.hpp"

#include <algorithm>

namespace rift::kernels {

void build_gather_positions(std::span<const int32_t> target_of, std::span<int32_t> ptr,
                            std::span<int32_t> pos) {
  std::fill(ptr.begin(), ptr.end(), 0);
  for (const int32_t t : target_of) ++ptr[static_cast<size_t>(t) + 1];
  for (size_t i = 1; i < ptr.size(); ++i) ptr[i] += ptr[i - 1];
  // ptr[t] is the next free position of target t while filling; shifted back afterwards.
  for (size_t s = 0; s < target_of.size(); ++s) pos[s] = ptr[target_of[s]]++;
  for (size_t i = ptr.size() - 1; i > 0; --i) ptr[i] = ptr[i - 1];
  ptr[0] = 0;
}

void gather_sum(std::span<const int32_t> ptr, std::span<const double> elem, std::span<double> out,
                size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    double s = 0.0;
    for (int32_t k = ptr[i]; k < ptr[i + 1]; ++k) s += elem[k];
    out[i] = s;
  }
}

void gather_sum3(std::span<const int32_t> ptr, std::span<const double> elem, std::span<double> out,
                 size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (int32_t k = ptr[i]; k < ptr[i + 1]; ++k) {
      s0 += elem[3 * static_cast<size_t>(k)];
      s1 += elem[3 * static_cast<size_t>(k) + 1];
      s2 += elem[3 * static_cast<size_t>(k) + 2];
    }
    out[3 * i] = s0;
    out[3 * i + 1] = s1;
    out[3 * i + 2] = s2;
  }
}

}  // namespace rift::kernels
