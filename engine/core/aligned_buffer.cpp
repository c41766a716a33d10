#include "engine/core/aligned_buffer.hpp"

#include <sys/mman.h>

#include <new>

namespace rift {

namespace {
// A step sweeps a few dozen columns of ~1e5-1e6 rows, and some accesses jump (the far side of a joint, a
// node's slot rows, contact pairs): with 4 KiB pages those miss the TLB as well as the cache. Columns of at
// least half a huge page get whole 2 MiB pages and MADV_HUGEPAGE, before anything touches them, since
// Debian's default transparent-huge-page mode serves only regions that ask ("madvise"). The rounding costs
// under 2 MiB per such column (at most doubling a 1 MiB one). Measured on the jointed 1e5-tet step at 2
// threads: +17 % (medians of 3 alternating rounds; only 2 MiB columns and up: +8 %); none beyond the noise
// at 1 thread (docs/performance.md). Advice only: where the kernel says no, the block keeps 4 KiB pages.
constexpr size_t kHugePage = size_t{2} << 20;
constexpr size_t kHugePageThreshold = kHugePage / 2;  // 1 MiB: the +17 % above; 2 MiB gave +8 %
}  // namespace

void AlignedBuffer::reserve(size_t bytes) {
  if (bytes <= capacity_) return;
  const bool huge = bytes >= kHugePageThreshold;
  const size_t align = huge ? kHugePage : alignment;
  const size_t rounded = (bytes + align - 1) / align * align;
  auto* fresh = static_cast<std::byte*>(std::aligned_alloc(align, rounded));
  if (!fresh) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  if (huge) madvise(fresh, rounded, MADV_HUGEPAGE);
#endif
  if (size_) std::memcpy(fresh, data_, size_);
  std::free(data_);
  data_ = fresh;
  capacity_ = rounded;
}

}  // namespace rift
