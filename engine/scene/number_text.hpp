#pragma once
// Numbers as scene files write them. Parsing is strict (the whole text must be one finite number, so
// "12abc", "1.0e-3.5", "nan" and "inf" are rejected); printing is the shortest text that reads back
// to the same double, so a resolved scene re-read gives bit-identical values.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rift {

enum class NumberParse { ok, not_a_number, not_finite, out_of_range };

// Decimal or scientific notation with an optional sign; integers are accepted as reals.
NumberParse parse_real_text(std::string_view text, double& out);
// Decimal digits with an optional sign; no fraction or exponent.
NumberParse parse_integer_text(std::string_view text, int64_t& out);

// Shortest round-trip text, e.g. "0.5", "2700", "1e-08".
std::string shortest_real(double value);
// Six significant digits, for numbers computed in messages ("0.1" rather than "0.10000000000000009").
std::string message_real(double value);
// Shortest round-trip text that YAML 1.1 readers (PyYAML) also take as a float: always has a '.'
// and a signed exponent, e.g. "0.5", "2700.0", "1.0e-08".
std::string yaml_real(double value);

}  // namespace rift
