#pragma once
// A forward-only tokenizer over a whole text file held in memory, tracking line numbers so that every
// parse error can say "path:line: expected ..., found ...". Tokens are whitespace-separated views into
// the text (no allocation); numbers are parsed with std::from_chars, which is exact and fast.
#include <cstdint>
#include <string>
#include <string_view>

namespace rift {

class TextCursor {
 public:
  TextCursor(std::string_view text, std::string path) : text_(text), path_(std::move(path)) {}

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

  int line() const { return token_line_; }  // line of the last token read (1-based)
  const std::string& path() const { return path_; }

  // Throws rift::Error "path:line: expected <expected>, found <found>".
  [[noreturn]] void fail(std::string_view expected, std::string_view found) const;
  [[noreturn]] void fail_at(int line, std::string_view expected, std::string_view found) const;
  // How a token reads in a message: 'tok' (its first 40 characters, control characters as '?'), or
  // "end of file" for the empty token.
  static std::string describe(std::string_view token);

 private:
  void skip_space();

  std::string_view text_;
  std::string path_;
  size_t pos_ = 0;
  int line_ = 1;        // line at pos_
  int token_line_ = 1;  // line of the last token
};

}  // namespace rift
