#include "engine/scene/number_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace rift {
namespace {

// from_chars takes no leading '+', which YAML allows.
std::string_view strip_plus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  return text;
}

}  // namespace

NumberParse parse_real_text(std::string_view text, double& out) {
  text = strip_plus(text);
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, out, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return NumberParse::out_of_range;
  if (ec != std::errc() || ptr != end) return NumberParse::not_a_number;
  if (!std::isfinite(out)) return NumberParse::not_finite;  // from_chars accepts "nan" and "inf"
  return NumberParse::ok;
}

NumberParse parse_integer_text(std::string_view text, int64_t& out) {
  text = strip_plus(text);
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, out, 10);
  if (ec == std::errc::result_out_of_range) return NumberParse::out_of_range;
  if (ec != std::errc() || ptr != end) return NumberParse::not_a_number;
  return NumberParse::ok;
}

std::string shortest_real(double value) {
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, ptr);
}

std::string message_real(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  return buf;
}

std::string yaml_real(double value) {
  std::string text = shortest_real(value == 0.0 ? 0.0 : value);  // no "-0"
  const size_t e = text.find('e');
  std::string mantissa = text.substr(0, e);
  std::string exponent = e == std::string::npos ? "" : text.substr(e);
  if (mantissa.find('.') == std::string::npos) mantissa += ".0";
  if (exponent.size() > 1 && exponent[1] != '-' && exponent[1] != '+') exponent = "e+" + exponent.substr(1);
  return mantissa + exponent;
}

}  // namespace rift
