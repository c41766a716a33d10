// Seeded fuzzing of the readers that take files from users: the scene reader, the MSH reader and the
// checkpoint verifier. Each starts from real inputs (the scenes in scenes/, a generated mesh, a written
// checkpoint), applies 1 - 4 random mutations (a byte replaced by a character YAML or MSH gives meaning,
// a span deleted, a line repeated, a hostile token inserted, the end cut off; in a binary MSH file also a
// 4- or 8-byte value overwritten with an edge value) and reads the result. The MSH reader is fuzzed on all
// four formats it takes (4.1 and 2.2, ASCII and binary). The
// promise checked: a reader returns, or throws rift::Error (which the CLI turns into exit 2 with the
// message); no other exception, no crash, no hang. The seed is fixed, so a failure names an input that
// reproduces: the test prints it. RIFT_FUZZ_CASES=<n> runs n cases per input file instead of the CI's
// number, and RIFT_FUZZ_TRACE=<file> writes each scene case there before it is read (the last one left
// is the one that crashed or hung). Found by it: a ',' at document level made yaml-cpp's LoadAll loop
// until memory ran out (scenes/bad/stray_comma.yaml). Last long run: 84,000 scene and 30,000 MSH cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/table.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "engine/scene/load_scene.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_msh_support.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

int cases(int ci_default) {
  const char* n = std::getenv("RIFT_FUZZ_CASES");
  return n ? std::max(1, std::atoi(n)) : ci_default;
}

class Mutator {
 public:
  // `binary`: the input holds binary data, which a further mutation aims at (a value overwritten).
  explicit Mutator(uint64_t seed, bool binary = false) : rng_(seed), binary_(binary) {}

  std::string operator()(std::string text) {
    const int n = pick(1, 4);
    for (int i = 0; i < n && !text.empty(); ++i) {
      const size_t at = static_cast<size_t>(pick(0, static_cast<int64_t>(text.size()) - 1));
      switch (pick(0, binary_ ? 5 : 4)) {
        case 0:
          text[at] = kChars[pick(0, sizeof kChars - 2)];
          break;
        case 1:
          text.erase(at, static_cast<size_t>(pick(1, 24)));
          break;
        case 2: {
          const size_t begin = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
          const size_t end = text.find('\n', at);
          const std::string line =
              text.substr(begin, end == std::string::npos ? std::string::npos : end - begin + 1);
          text.insert(begin, line);
          break;
        }
        case 3:
          text.insert(at, kTokens[pick(0, std::size(kTokens) - 1)]);
          break;
        case 5: {  // a binary int or size_t overwritten with an edge value (little-endian)
          const uint64_t value = kValues[pick(0, std::size(kValues) - 1)];
          const size_t bytes = std::min<size_t>(pick(0, 1) ? 8 : 4, text.size() - at);
          for (size_t k = 0; k < bytes; ++k) text[at + k] = static_cast<char>(value >> (8 * k));
          break;
        }
        default:
          text.resize(at);
      }
    }
    return text;
  }

  int64_t pick(int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng_); }

 private:
  static constexpr char kChars[] = ":-[]{}\n \t\"'*&!|>%@`#,.0123456789$eE+";
  static constexpr const char* kTokens[] = {
      "1e308", "-1e308", "nan",  ".inf",       "-.inf",       "99999999999999999999",
      "0",     "-0",     "-1",   "null",       "~",           "[]",
      "{}",    "&a ",    "*a",   "<<: *a",     "!!binary ",   "\n- ",
      ": ",    "$End",   "4.1 ", "2147483648", "-2147483649", "\xff\xfe",
      "\0"};
  static constexpr uint64_t kValues[] = {
      0, 1, 4, 0x7fffffff, 0x80000000, 0xffffffff, uint64_t{1} << 40, ~uint64_t{0} >> 1, ~uint64_t{0}};
  std::mt19937_64 rng_;
  bool binary_;
};

// Reads `what` with `read`; a failure message carries the case's number and the input's start.
template <class Read>
void expect_reads_or_errors(const std::string& label, const std::string& input, Read&& read) {
  try {
    read();
  } catch (const Error&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << label << ": " << typeid(e).name() << ": " << e.what() << "\ninput:\n"
                  << input.substr(0, 2000);
  }
}

std::vector<fs::path> scene_files() {
  std::vector<fs::path> files;
  for (const char* dir : {"scenes/examples", "scenes/validation", "scenes/bad"})
    for (const auto& e : fs::directory_iterator(fs::path(RIFT_SOURCE_DIR) / dir))
      if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(Fuzz, SceneReaderReturnsOrErrorsOnMutatedScenes) {
  const auto files = scene_files();
  ASSERT_GT(files.size(), 20u);
  const int per_file = cases(40);
  size_t accepted = 0, total = 0;
  for (size_t f = 0; f < files.size(); ++f) {
    const std::string original = slurp(files[f]);
    Mutator mutate(1000 + f);
    for (int k = 0; k < per_file; ++k) {
      const std::string text = mutate(original);
      const std::string label = files[f].filename().string() + " case " + std::to_string(k);
      if (std::getenv("RIFT_FUZZ_TRACE")) {
        std::fprintf(stderr, "%s\n", label.c_str());
        std::ofstream(std::getenv("RIFT_FUZZ_TRACE"), std::ios::binary | std::ios::trunc) << text;
      }
      expect_reads_or_errors(label, text, [&] {
        const SceneLoadResult r = read_scene_text(text, label, files[f].parent_path().string());
        accepted += r.scene.has_value();
      });
      ++total;
    }
  }
  std::printf("%zu mutated scenes read: %zu accepted, the rest refused with diagnostics\n", total, accepted);
}

// Reads `n` mutations of `original` (one MSH format) through the default window and a small one.
void fuzz_msh(const test::TempDir& dir, const std::string& name, const std::string& original, Mutator mutate,
              int n) {
  size_t accepted = 0;
  for (int k = 0; k < n; ++k) {
    const std::string text = mutate(original);
    const fs::path file = dir / "case.msh";
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
    // Read through the default window and through a small one that the tokens cross at every offset:
    // the same mesh or the same message, unless a token is longer than the small window.
    std::string outcome[2];
    const size_t windows[2] = {msh_window_bytes, 24 + static_cast<size_t>(k % 97)};
    for (int w = 0; w < 2; ++w)
      expect_reads_or_errors(name + " case " + std::to_string(k), text, [&] {
        try {
          const TetMesh m =
              read_msh(file.string(), 1.0, nullptr, {1u << 20, "mesh.max_file_bytes"}, windows[w]);
          outcome[w] = "read " + std::to_string(m.nodes.size()) + " nodes " + std::to_string(m.tets.size()) +
                       " tets " + std::to_string(m.triangles.size()) + " triangles";
          accepted += w == 0 && !m.tets.empty();
        } catch (const Error& e) {
          outcome[w] = e.what();
          throw;
        }
      });
    if (outcome[1].find("expected a token or quoted string of at most") == std::string::npos) {
      EXPECT_EQ(outcome[1], outcome[0]) << name << " case " << k << " through a window of " << windows[1];
    }
  }
  std::printf("%d mutated %s meshes read: %zu accepted, the rest refused\n", n, name.c_str(), accepted);
}

// The same lattice box in the four formats the MSH reader takes: Rift's own 4.1 ASCII file and the test
// writer's 4.1 binary and 2.2 ASCII and binary (test_msh_support.hpp).
TEST(Fuzz, MshReaderReturnsOrErrorsOnMutatedMeshes) {
  test::TempDir dir;
  TetMesh mesh = generate_lattice_box({2, 2, 2}, {1, 1, 1});
  write_msh(mesh, (dir / "base.msh").string());
  const test::MshSpec spec = test::spec_of(mesh);
  const struct {
    const char* name;
    std::string bytes;
    bool binary;
    uint64_t seed;
    int cases;
  } inputs[] = {{"4.1 ASCII", slurp(dir / "base.msh"), false, 2026, 600},
                {"4.1 binary", test::write_msh41(spec, true), true, 2027, 400},
                {"2.2 ASCII", test::write_msh22(spec, false), false, 2028, 400},
                {"2.2 binary", test::write_msh22(spec, true), true, 2029, 400}};
  for (const auto& input : inputs) {
    ASSERT_EQ(read_msh(test::write_bytes(dir, "unmutated.msh", input.bytes)).tets, mesh.tets) << input.name;
    fuzz_msh(dir, input.name, input.bytes, Mutator(input.seed, input.binary), cases(input.cases));
  }
}

// A checkpoint of a small store, damaged: 1 - 4 bytes changed anywhere (the seal, HDF5's own structure,
// the columns' values), or the file cut short. verify_checkpoint and read_checkpoint must report it; the
// seal (file_seal.hpp) finds it before HDF5 parses anything, which matters: HDF5 1.10.8 reads damaged
// metadata unsafely (AddressSanitizer found a heap-use-after-free in H5Aopen_by_name on such a file).
TEST(Fuzz, CheckpointReaderReturnsOrErrorsOnDamagedFiles) {
  auto build = [](Store& store) {
    Table& nodes = store.add_table("solid_node");
    nodes.add<double>("x", 3);
    nodes.add<int32_t>("id");
    nodes.resize(64);
  };
  Store store;
  build(store);
  auto x = store.table("solid_node").span<double>("x");
  for (size_t i = 0; i < x.size(); ++i) x[i] = 1e-3 * static_cast<double>(i);
  CheckpointMeta meta;
  meta.step = 10;
  meta.time = 1e-6;
  meta.dt = 1e-7;
  meta.scene_hash = "fnv1a64:0123456789abcdef";
  meta.resolved_scene = "scene:\n  name: fuzz\n";
  meta.rift_version = "0.1.0";
  test::TempDir dir;
  write_checkpoint(dir / "base.h5", store, meta);
  const std::string original = slurp(dir / "base.h5");
  std::mt19937_64 rng(42);
  auto pick = [&](size_t lo, size_t hi) { return std::uniform_int_distribution<size_t>(lo, hi)(rng); };
  const int n = cases(300);
  size_t accepted = 0;
  for (int k = 0; k < n; ++k) {
    std::string bytes = original;
    if (pick(0, 4) == 0) {
      bytes.resize(pick(0, bytes.size() - 1));
    } else {
      for (size_t m = pick(1, 4); m > 0; --m)
        bytes[pick(0, bytes.size() - 1)] ^= static_cast<char>(pick(1, 255));
    }
    const fs::path file = dir / "case.h5";
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    expect_reads_or_errors("checkpoint case " + std::to_string(k), "(binary)", [&] {
      verify_checkpoint(file);
      Store fresh;
      build(fresh);
      const CheckpointMeta read = read_checkpoint(file, fresh);
      // What is read despite the damage must be exactly what was written.
      for (const auto& column : store.table("solid_node").columns()) {
        const Column& back = fresh.table("solid_node").column(column->name());
        ASSERT_EQ(back.bytes(), column->bytes()) << "case " << k;
        EXPECT_EQ(std::memcmp(back.data(), column->data(), column->bytes()), 0)
            << "case " << k << ": " << column->name();
      }
      EXPECT_EQ(read.step, meta.step) << "case " << k;
      EXPECT_EQ(read.resolved_scene, meta.resolved_scene) << "case " << k;
      ++accepted;
    });
  }
  std::printf("%d damaged checkpoints read: %zu accepted\n", n, accepted);
}

}  // namespace
}  // namespace rift
