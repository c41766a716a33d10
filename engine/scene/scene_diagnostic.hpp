#pragma once
// One problem found in a scene: where it is, which key, what was expected and what was found. The
// scene reader collects all of them for a file so the user fixes everything in one pass.
#include <string>

namespace rift {

struct SceneDiagnostic {
  std::string file;      // scene file label, or "--set key=value" when an override is at fault
  int line = 0;          // 1-based; 0 when there is no line (override, unreadable file)
  int column = 0;        // 1-based; 0 when unknown
  std::string key_path;  // e.g. "solid.materials[0].density"; "" for file-level problems
  std::string expected;  // type, unit and range the key accepts
  std::string found;     // what the file holds there
  std::string hint;      // optional advice, e.g. "did you mean 'solid'?"

  // "file:line:col: key.path: expected X, found Y (hint)"; line/column and key are left out when unknown.
  std::string format() const;
};

}  // namespace rift
