#include "engine/mesh/msh_fields.hpp"

#include <algorithm>
#include <bit>
#include <limits>

#include "engine/core/error.hpp"

namespace rift {
namespace {

// Binary MSH data is little-endian (a big-endian file is refused at its $MeshFormat).
template <class T>
void from_little_endian(T* values, size_t n) {
  if constexpr (std::endian::native == std::endian::big) {
    for (size_t i = 0; i < n; ++i) {
      char* b = reinterpret_cast<char*>(values + i);
      std::reverse(b, b + sizeof(T));
    }
  }
}

}  // namespace

std::string_view MshFields::token() {
  last_is_text_ = true;
  return cur_->token();
}

int64_t MshFields::text_integer(std::string_view what) {
  last_is_text_ = true;
  return cur_->integer(what);
}

void MshFields::expect_end(std::string_view end_marker) {
  const std::string_view t = token();
  if (t != end_marker) cur_->fail(std::string(end_marker), TextCursor::describe(t));
}

void MshFields::begin_data() {
  if (!binary_) return;
  if (!cur_->line_end())
    fail_at_offset(cur_->offset(), "the end of the text line before the binary data", "other bytes");
}

void MshFields::read_binary(void* out, size_t bytes, std::string_view what) {
  last_is_text_ = false;
  last_offset_ = cur_->offset();
  if (!cur_->bytes(static_cast<char*>(out), bytes)) fail_at_offset(last_offset_, what, "end of file");
}

int MshFields::int32(std::string_view what) {
  int value = 0;
  int32s(&value, 1, what);
  return value;
}

int64_t MshFields::size(std::string_view what) {
  int64_t value = 0;
  sizes(&value, 1, what);
  return value;
}

double MshFields::real(std::string_view what) {
  double value = 0;
  reals(&value, 1, what);
  return value;
}

void MshFields::int32s(int* out, size_t n, std::string_view what) {
  if (binary_) {
    static_assert(sizeof(int) == 4);
    read_binary(out, n * sizeof(int), what);
    from_little_endian(out, n);
    return;
  }
  last_is_text_ = true;
  for (size_t i = 0; i < n; ++i) {
    const int64_t v = cur_->integer(what);
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      cur_->fail(std::string(what) + " within the range of int", std::to_string(v));
    out[i] = static_cast<int>(v);
  }
}

void MshFields::sizes(int64_t* out, size_t n, std::string_view what) {
  if (binary_) {
    read_binary(out, n * sizeof(int64_t), what);
    from_little_endian(out, n);
    for (size_t i = 0; i < n; ++i)
      if (out[i] < 0)
        fail_at_offset(last_offset_ + 8 * i, std::string(what) + " (a size_t below 2^63)",
                       std::to_string(static_cast<uint64_t>(out[i])));
    return;
  }
  last_is_text_ = true;
  for (size_t i = 0; i < n; ++i) out[i] = cur_->integer(what);
}

void MshFields::reals(double* out, size_t n, std::string_view what) {
  if (binary_) {
    static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559);
    read_binary(out, n * sizeof(double), what);
    from_little_endian(out, n);
    return;
  }
  last_is_text_ = true;
  for (size_t i = 0; i < n; ++i) out[i] = cur_->real(what);
}

void MshFields::skip_bytes(uint64_t n, std::string_view what) {
  last_is_text_ = false;
  last_offset_ = cur_->offset();
  if (!cur_->skip_bytes(n)) fail_at_offset(last_offset_, what, "end of file");
}

int64_t MshFields::count(int64_t n, std::string_view what, uint64_t binary_bytes) {
  if (n < 0) fail(std::string(what) + " >= 0", std::to_string(n));
  if (static_cast<uint64_t>(n) > file_size_ / (binary_ ? binary_bytes : 2))
    fail(std::string(what) + " that fits in the file's size", std::to_string(n));
  return n;
}

std::string MshFields::where(uint64_t position) const {
  return (binary_ ? "byte offset " : "line ") + std::to_string(position);
}

std::string MshFields::at(uint64_t position) const {
  return (binary_ ? "at " : "on ") + where(position);
}

void MshFields::fail(std::string_view expected, std::string_view found) const {
  if (last_is_text_) cur_->fail(expected, found);
  fail_at_offset(last_offset_, expected, found);
}

void MshFields::fail_at(uint64_t position, std::string_view expected, std::string_view found) const {
  if (!binary_) cur_->fail_at(static_cast<int>(position), expected, found);
  fail_at_offset(position, expected, found);
}

void MshFields::fail_at_offset(uint64_t offset, std::string_view expected, std::string_view found) const {
  throw Error(cur_->path() + ": byte offset " + std::to_string(offset) + ": expected " +
              std::string(expected) + ", found " + std::string(found));
}

}  // namespace rift
