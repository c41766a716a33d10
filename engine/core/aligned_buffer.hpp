#pragma once
// A growable, 64-byte aligned block of bytes: the storage behind every column. Cache-line alignment
// lets kernels use aligned vector loads and keeps two threads' writes to different columns apart.
// Blocks of 1 MiB or more get whole 2 MiB pages and ask for transparent huge pages (aligned_buffer.cpp).
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace rift {

class AlignedBuffer {
 public:
  static constexpr size_t alignment = 64;

  AlignedBuffer() = default;
  AlignedBuffer(const AlignedBuffer& other) { *this = other; }
  AlignedBuffer(AlignedBuffer&& other) noexcept { swap(other); }
  AlignedBuffer& operator=(const AlignedBuffer& other) {
    if (this != &other) {
      resize(other.size_);
      if (size_) std::memcpy(data_, other.data_, size_);
    }
    return *this;
  }
  AlignedBuffer& operator=(AlignedBuffer&& other) noexcept {
    swap(other);
    return *this;
  }
  ~AlignedBuffer() { std::free(data_); }

  void swap(AlignedBuffer& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    std::swap(capacity_, other.capacity_);
  }

  // Keeps the first min(old, new) bytes, zero-fills the rest. Reallocates only when growing past capacity.
  void resize(size_t bytes) {
    if (bytes > capacity_) reserve(bytes + bytes / 2);
    if (bytes > size_) std::memset(data_ + size_, 0, bytes - size_);
    size_ = bytes;
  }
  void reserve(size_t bytes);

  std::byte* data() { return data_; }
  const std::byte* data() const { return data_; }
  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }

 private:
  std::byte* data_ = nullptr;
  size_t size_ = 0;
  size_t capacity_ = 0;
};

}  // namespace rift
