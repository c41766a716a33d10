// docs/scene-format.md: the embedded text, its key tables and its complete examples. See
// scene_format_doc.hpp.
#include "engine/scene/scene_format_doc.hpp"

#include "rift/scene_format_doc.hpp"

namespace rift {
namespace {

std::string trimmed(std::string_view s) {
  const size_t first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return std::string(s.substr(first, s.find_last_not_of(" \t") - first + 1));
}

// The cells of a table row "| a | b | ... |". A pipe written as "\|" is text. A row with more cells
// than its header (a meaning with unescaped pipes) gives the extra ones back to its last cell.
std::vector<std::string> cells(std::string_view line, size_t columns) {
  std::vector<std::string> out;
  std::string cell;
  for (size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      out.push_back(trimmed(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  if (!trimmed(cell).empty()) out.push_back(trimmed(cell));
  while (columns > 0 && out.size() > columns) {
    out[out.size() - 2] += " | " + out.back();
    out.pop_back();
  }
  return out;
}

std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> out;
  for (size_t start = 0; start < text.size();) {
    const size_t end = text.find('\n', start);
    const size_t stop = end == std::string_view::npos ? text.size() : end;
    out.push_back(text.substr(start, stop - start));
    start = stop + 1;
  }
  return out;
}

// A data row under `header`: each cell goes to the field its column names.
DocumentedKey row_of(std::string_view line, const std::vector<std::string>& header) {
  DocumentedKey k;
  const size_t end = line.find('`', 3);
  k.key = std::string(line.substr(3, end - 3));
  const std::vector<std::string> row = cells(line, header.size());
  for (size_t c = 1; c < row.size(); ++c) {
    const std::string name = c < header.size() ? header[c] : "";
    if (name == "type") k.type = row[c];
    if (name == "unit") k.unit = row[c];
    if (name == "default") k.default_value = row[c];
    if (name == "range" || name == "allowed") k.range = row[c];
    if (name == "meaning" || name == "holds") k.meaning = row[c];
  }
  return k;
}

}  // namespace

std::string_view scene_format_doc() {
  static const std::string text = [] {
    std::string joined;
    for (std::string_view part : generated::scene_format_doc_parts) joined += part;
    return joined;
  }();
  return text;
}

std::map<std::string, DocumentedKey> documented_keys(std::string_view doc) {
  std::map<std::string, DocumentedKey> keys;
  const std::vector<std::string_view> lines = lines_of(doc);
  std::vector<std::string> header;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = lines[i];
    if (line.rfind("|", 0) != 0) {
      header.clear();
      continue;
    }
    if (header.empty() && i + 1 < lines.size() && lines[i + 1].rfind("|---", 0) == 0) {
      header = cells(line, 0);
      continue;
    }
    if (line.rfind("| `", 0) != 0 || line.find('`', 3) == std::string_view::npos) continue;
    DocumentedKey k = row_of(line, header);
    keys.emplace(k.key, std::move(k));
  }
  return keys;
}

std::vector<std::string> complete_examples(std::string_view text) {
  std::vector<std::string> out;
  for (size_t heading = text.find("## Complete example"); heading != std::string_view::npos;
       heading = text.find("## Complete example", heading + 1)) {
    const size_t open = text.find("```yaml\n", heading);
    const size_t close = open == std::string_view::npos ? open : text.find("```", open + 8);
    if (open == std::string_view::npos || close == std::string_view::npos) return {};
    out.emplace_back(text.substr(open + 8, close - open - 8));
  }
  return out;
}

}  // namespace rift
