#include "engine/mesh/text_cursor.hpp"

#include <algorithm>
#include <charconv>

#include "engine/core/error.hpp"

namespace rift {

void TextCursor::skip_space() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
    } else if (c != ' ' && c != '\t' && c != '\r') {
      break;
    }
    ++pos_;
  }
}

std::string_view TextCursor::token() {
  skip_space();
  token_line_ = line_;
  const size_t start = pos_;
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == ' ' || c == '\n' || c == '\t' || c == '\r') break;
    ++pos_;
  }
  return text_.substr(start, pos_ - start);
}

std::string_view TextCursor::peek() {
  const size_t pos = pos_;
  const int line = line_, token_line = token_line_;
  const std::string_view t = token();
  pos_ = pos;
  line_ = line;
  token_line_ = token_line;
  return t;
}

int64_t TextCursor::integer(std::string_view what) {
  const std::string_view t = token();
  int64_t value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size())
    fail(std::string(what) + " (an integer)", describe(t));
  return value;
}

double TextCursor::real(std::string_view what) {
  const std::string_view t = token();
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size())
    fail(std::string(what) + " (a number)", describe(t));
  return value;
}

std::string TextCursor::quoted(std::string_view what) {
  skip_space();
  token_line_ = line_;
  if (pos_ >= text_.size() || text_[pos_] != '"')
    fail(std::string(what) + " in double quotes", describe(peek()));
  const size_t close = text_.find_first_of("\"\n", pos_ + 1);
  if (close == std::string_view::npos || text_[close] != '"')
    fail(std::string(what) + " with a closing double quote on the same line", "none");
  std::string value(text_.substr(pos_ + 1, close - pos_ - 1));
  pos_ = close + 1;
  return value;
}

void TextCursor::skip_rest_of_line() {
  const size_t nl = text_.find('\n', pos_);
  if (nl == std::string_view::npos) {
    pos_ = text_.size();
  } else {
    pos_ = nl + 1;
    ++line_;
  }
}

bool TextCursor::skip_past_line_starting(std::string_view marker) {
  // Scan whole lines: unknown sections ($NodeData of a million values) are skipped at memory speed.
  size_t line_start = pos_;
  while (line_start < text_.size()) {
    const size_t nl = text_.find('\n', line_start);
    const size_t line_end = nl == std::string_view::npos ? text_.size() : nl;
    std::string_view line = text_.substr(line_start, line_end - line_start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (line == marker) {
      line_ += static_cast<int>(std::count(text_.begin() + pos_, text_.begin() + line_start, '\n'));
      token_line_ = line_;
      pos_ = line_end;
      return true;
    }
    line_start = line_end + 1;
  }
  return false;
}

std::string TextCursor::describe(std::string_view token) {
  if (token.empty()) return "end of file";
  const bool cut = token.size() > 40;
  std::string shown(token.substr(0, 40));
  // Control characters of a binary file would reach the terminal as they are.
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return "'" + shown + (cut ? "...'" : "'");
}

void TextCursor::fail(std::string_view expected, std::string_view found) const {
  fail_at(token_line_, expected, found);
}

void TextCursor::fail_at(int line, std::string_view expected, std::string_view found) const {
  throw Error(path_ + ":" + std::to_string(line) + ": expected " + std::string(expected) + ", found " +
              std::string(found));
}

}  // namespace rift
