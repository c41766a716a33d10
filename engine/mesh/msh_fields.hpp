#pragma once
// The values of an MSH file's sections, read either as ASCII tokens or, in a binary file, as the binary
// values Gmsh writes there (little-endian; int: 4 bytes, size_t and double: 8), so that one parser reads
// both file types of a format version. Errors say "path:line: expected ..., found ..." for text and
// "path: byte offset N: expected ..., found ..." for binary data, where a line means nothing.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "engine/mesh/text_cursor.hpp"

namespace rift {

class MshFields {
 public:
  MshFields(TextCursor& cur, bool binary, uint64_t file_size)
      : cur_(&cur), binary_(binary), file_size_(file_size) {}

  bool binary() const { return binary_; }
  TextCursor& cursor() { return *cur_; }

  // Text, in either file type (section names, the counts of MSH 2.2's binary sections).
  std::string_view token();
  int64_t text_integer(std::string_view what);
  void expect_end(std::string_view end_marker);  // the token `end_marker` ("$EndNodes")
  // Where the binary data of a section starts: the end of the text line (nothing in an ASCII file).
  void begin_data();

  // One value, or `n` of them (a binary file reads them in one piece). `what` names them in errors.
  int int32(std::string_view what);     // int
  int64_t size(std::string_view what);  // size_t: in a binary file below 2^63
  double real(std::string_view what);   // double
  void int32s(int* out, size_t n, std::string_view what);
  void sizes(int64_t* out, size_t n, std::string_view what);
  void reals(double* out, size_t n, std::string_view what);
  // Skips `n` binary bytes of records named `what`.
  void skip_bytes(uint64_t n, std::string_view what);

  // `n` checked as a count of records that each take at least `binary_bytes` bytes in a binary file (2 in
  // an ASCII one: a digit and a separator), so that no count sizes an allocation beyond the file's size.
  int64_t count(int64_t n, std::string_view what, uint64_t binary_bytes);

  // Where the last value was: its line (text) or byte offset (binary data).
  uint64_t position() const { return last_is_text_ ? static_cast<uint64_t>(cur_->line()) : last_offset_; }
  // A stored position() of an element or node, which lies in text in an ASCII file and in binary data in
  // a binary one: "line 12" / "byte offset 345", and "on line 12" / "at byte offset 345".
  std::string where(uint64_t position) const;
  std::string at(uint64_t position) const;

  [[noreturn]] void fail(std::string_view expected, std::string_view found) const;  // at the last value
  [[noreturn]] void fail_at(uint64_t position, std::string_view expected, std::string_view found) const;

 private:
  void read_binary(void* out, size_t bytes, std::string_view what);
  [[noreturn]] void fail_at_offset(uint64_t offset, std::string_view expected, std::string_view found) const;

  TextCursor* cur_;
  bool binary_;
  uint64_t file_size_;
  bool last_is_text_ = true;
  uint64_t last_offset_ = 0;
};

}  // namespace rift
