#include "engine/mesh/text_cursor.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"

namespace rift {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\t' || c == '\r';
}

}  // namespace

TextCursor::TextCursor(InputFileReader& source, std::string path, size_t window_bytes)
    : source_(&source),
      window_(std::max<size_t>(window_bytes, 16)),
      hash_(fnv1a64_basis),
      path_(std::move(path)) {}

bool TextCursor::more(size_t& keep_from) {
  if (at_eof_) return false;
  const size_t kept = end_ - keep_from;
  if (kept == window_.size())
    fail("a token or quoted string of at most " + std::to_string(window_.size()) + " bytes", "a longer one");
  std::memmove(window_.data(), window_.data() + keep_from, kept);
  window_start_ += keep_from;
  pos_ -= keep_from;
  keep_from = 0;
  end_ = kept;
  const size_t got = source_->read_some(window_.data() + end_, window_.size() - end_);
  hash_ = fnv1a64(window_.data() + end_, got, hash_);
  end_ += got;
  at_eof_ = got == 0;
  return got > 0;
}

void TextCursor::skip_space() {
  for (;;) {
    while (pos_ < end_) {
      const char c = data()[pos_];
      if (c == '\n')
        ++line_;
      else if (c != ' ' && c != '\t' && c != '\r')
        return;
      ++pos_;
    }
    size_t keep = pos_;
    if (!more(keep)) return;
  }
}

std::string_view TextCursor::token() {
  skip_space();
  token_line_ = line_;
  size_t start = pos_;
  for (;;) {
    while (pos_ < end_ && !is_space(data()[pos_])) ++pos_;
    if (pos_ < end_ || !more(start)) break;
  }
  return {data() + start, pos_ - start};
}

std::string_view TextCursor::peek() {
  const int token_line = token_line_;
  const std::string_view t = token();
  pos_ -= t.size();  // a token holds no newline: line_ is the token's line
  line_ = token_line_;
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
  if (pos_ >= end_ || data()[pos_] != '"') fail(std::string(what) + " in double quotes", describe(peek()));
  size_t scanned = 1;  // bytes after pos_ known to hold no quote and no newline
  const char* close = nullptr;
  for (;;) {
    const char* from = data() + pos_ + scanned;
    const char* stop = data() + end_;
    close = std::find_if(from, stop, [](char c) { return c == '"' || c == '\n'; });
    if (close != stop) break;
    scanned = end_ - pos_;
    size_t keep = pos_;
    if (!more(keep)) {  // the end of the file (more() may have moved the text: `close` is stale)
      close = nullptr;
      break;
    }
  }
  if (close == nullptr || *close != '"')
    fail(std::string(what) + " with a closing double quote on the same line", "none");
  const size_t length = static_cast<size_t>(close - (data() + pos_)) - 1;
  std::string value(data() + pos_ + 1, length);
  pos_ += length + 2;
  return value;
}

void TextCursor::skip_rest_of_line() {
  for (;;) {
    const void* nl = std::memchr(data() + pos_, '\n', end_ - pos_);
    if (nl) {
      pos_ = static_cast<size_t>(static_cast<const char*>(nl) - data()) + 1;
      ++line_;
      return;
    }
    pos_ = end_;
    size_t keep = pos_;
    if (!more(keep)) return;
  }
}

bool TextCursor::skip_past_line_starting(std::string_view marker) {
  // Whole lines are scanned, not tokens: unknown sections ($NodeData of a million values) are skipped at
  // memory speed. pos_ stays at the start of the line being examined; a line longer than the window is
  // dropped as it is read and cannot be the marker.
  size_t scanned = 0;  // bytes after pos_ known to hold no newline
  bool too_long = false;
  for (;;) {
    const void* found = std::memchr(data() + pos_ + scanned, '\n', end_ - pos_ - scanned);
    size_t line_end = found ? static_cast<size_t>(static_cast<const char*>(found) - data()) : end_;
    if (!found && !at_eof_) {
      if (pos_ == 0 && end_ == window_.size()) {
        too_long = true;
        pos_ = end_;
      }
      scanned = end_ - pos_;
      size_t keep = pos_;
      more(keep);
      continue;
    }
    std::string_view line(data() + pos_, line_end - pos_);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (!too_long && line == marker) {
      token_line_ = line_;
      pos_ = line_end;
      return true;
    }
    if (!found) {
      pos_ = end_;
      return false;
    }
    pos_ = line_end + 1;
    ++line_;
    scanned = 0;
    too_long = false;
  }
}

bool TextCursor::bytes(char* out, size_t n) {
  for (;;) {
    const size_t take = std::min(n, end_ - pos_);
    if (take > 0) {
      const char* from = data() + pos_;
      std::memcpy(out, from, take);
      line_ += static_cast<int>(std::count(from, from + take, '\n'));
      pos_ += take;
      out += take;
      n -= take;
    }
    if (n == 0) return true;
    size_t keep = pos_;
    if (!more(keep)) return false;
  }
}

bool TextCursor::skip_bytes(uint64_t n) {
  for (;;) {
    const size_t take = static_cast<size_t>(std::min<uint64_t>(n, end_ - pos_));
    const char* from = data() + pos_;
    line_ += static_cast<int>(std::count(from, from + take, '\n'));
    pos_ += take;
    n -= take;
    if (n == 0) return true;
    size_t keep = pos_;
    if (!more(keep)) return false;
  }
}

bool TextCursor::line_end() {
  for (;;) {
    while (pos_ < end_) {
      const char c = data()[pos_];
      if (c == '\n') {
        ++pos_;
        ++line_;
        return true;
      }
      if (c != ' ' && c != '\t' && c != '\r') return false;
      ++pos_;
    }
    size_t keep = pos_;
    if (!more(keep)) return false;
  }
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
