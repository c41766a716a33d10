#pragma once
// FNV-1a 64: a small, fast, non-cryptographic hash. Rift uses it to identify a resolved scene and the
// mesh files it reads, and to find damaged checkpoint data. It detects accidental change (a flipped
// byte, a truncated or replaced file), not data someone forged on purpose.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace rift {

inline constexpr uint64_t fnv1a64_basis = 14695981039346656037ull;  // FNV-1a 64 offset basis

// Continues the hash `h` over `size` bytes, so that data arriving in pieces hashes like one block.
inline uint64_t fnv1a64(const void* data, size_t size, uint64_t h = fnv1a64_basis) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;  // FNV 64 prime
  }
  return h;
}

// 16 lowercase hex digits.
inline std::string hex16(uint64_t value) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
  return buf;
}

}  // namespace rift
