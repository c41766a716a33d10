#pragma once
// A forward-only tokenizer over a text file, tracking line numbers so that every parse error can say
// "path:line: expected ..., found ...". The file is streamed through a window of fixed size, so that
// reading a mesh of gigabytes needs the window, not the file, in memory. Tokens are whitespace-separated
// views into the window (no allocation), valid until the next call; numbers are parsed with
// std::from_chars, which is exact and fast. A file may mix text and raw bytes (binary MSH files put binary
// data between text lines): raw reads copy or skip any number of bytes across the window's boundaries.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/input_file.hpp"

namespace rift {

class TextCursor {
 public:
  // Over a file read through `source`, `window_bytes` at a time: a token or quoted string longer than the
  // window is an error; a longer line is fine where it is skipped.
  TextCursor(InputFileReader& source, std::string path, size_t window_bytes);

  // The next whitespace-separated token, or "" at the end of the text.
  std::string_view token();
  // The next token without consuming it.
  std::string_view peek();
  // The next token as a number; `what` names it in the error ("number of nodes").
  int64_t integer(std::string_view what);
  double real(std::string_view what);
  // A double-quoted string on the current line ("my surface"); returns it without the quotes.
  std::string quoted(std::string_view what);
  // Consumes the rest of the current line including its newline.
  void skip_rest_of_line();
  // Skips past the next occurrence of `marker` at the start of a line; false when there is none.
  bool skip_past_line_starting(std::string_view marker);

  // Raw bytes: exactly `n` into `out`; false when the file ends first (what there was is consumed).
  // Newline bytes among them count as lines, so that the lines after binary data are numbered as an
  // editor numbers them.
  bool bytes(char* out, size_t n);
  // Skips `n` raw bytes (hashed like the rest); false when the file ends first.
  bool skip_bytes(uint64_t n);
  // The end of a text line before raw bytes start: spaces, tabs and carriage returns, then one newline,
  // consumed. False when another byte (or the end of the file) comes first.
  bool line_end();
  uint64_t offset() const { return window_start_ + pos_; }  // byte offset of the next unread byte

  int line() const { return token_line_; }  // line of the last token read (1-based)
  const std::string& path() const { return path_; }
  // FNV-1a 64 of every byte read so far (of the whole file once the last token has been read).
  uint64_t content_hash() const { return hash_; }

  // Throws rift::Error "path:line: expected <expected>, found <found>".
  [[noreturn]] void fail(std::string_view expected, std::string_view found) const;
  [[noreturn]] void fail_at(int line, std::string_view expected, std::string_view found) const;
  // How a token reads in a message: 'tok' (its first 40 characters, control characters as '?'), or
  // "end of file" for the empty token.
  static std::string describe(std::string_view token);

 private:
  void skip_space();
  // Reads more of the file behind the text at hand, first dropping what lies before `keep_from` (which
  // becomes 0; pos_ moves with it). False at the end of the file.
  bool more(size_t& keep_from);
  const char* data() const { return window_.data(); }

  InputFileReader* source_;
  std::vector<char> window_;
  bool at_eof_ = false;
  uint64_t hash_ = 0;
  uint64_t window_start_ = 0;  // byte offset in the file of window_[0]
  std::string path_;
  size_t pos_ = 0, end_ = 0;  // next byte and end of the text at hand
  int line_ = 1;              // line at pos_
  int token_line_ = 1;        // line of the last token
};

}  // namespace rift
