#pragma once
// "Did you mean ...?" for misspelt keys and choices.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rift {

// Edit distance counting insertions, deletions, substitutions and swaps of neighbours as one edit each
// (optimal string alignment), so "soild" is one edit from "solid".
int edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word` if it is close enough to be a likely typo (at most 2 edits, or a
// third of the word for long words), else "". Ties go to the earlier candidate.
std::string closest_match(std::string_view word, std::span<const std::string> candidates);

// "did you mean 'x'?" or "".
std::string did_you_mean(std::string_view word, std::span<const std::string> candidates);

// " (did you mean 'x'?)" to append to a message, or "" when there is no suggestion.
inline std::string hint(const std::string& suggestion) {
  return suggestion.empty() ? std::string() : " (" + suggestion + ")";
}

// "a, b, c" for listing the valid names in a message; "(none)" for an empty list.
inline std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none)" : out;
}

}  // namespace rift
