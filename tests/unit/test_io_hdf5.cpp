// The HDF5 wrapper: every element type round-trips bit for bit, in both storage layouts, and
// attributes, strings, listings and errors behave as documented.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/io/hdf5_file.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

// Values that catch conversions: extremes, negative zero, NaN with a payload, denormals.
template <class T>
std::vector<T> sample(size_t n) {
  std::vector<T> v(n);
  uint64_t state = 88172645463325252ull;  // xorshift64: arbitrary but reproducible bit patterns
  for (size_t i = 0; i < n; ++i) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    if constexpr (std::is_floating_point_v<T>) {
      using Bits = std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>;
      Bits bits = static_cast<Bits>(state);
      std::memcpy(&v[i], &bits, sizeof bits);
    } else {
      v[i] = static_cast<T>(state);
    }
  }
  if constexpr (std::is_floating_point_v<T>) {
    if (n > 4) {
      v[0] = -0.0;
      v[1] = std::numeric_limits<T>::denorm_min();
      v[2] = std::numeric_limits<T>::infinity();
      v[3] = std::bit_cast<T>(std::bit_cast<std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>>(
                                  std::numeric_limits<T>::quiet_NaN()) |
                              1u);  // NaN with a payload bit
    }
  } else if (n > 2) {
    v[0] = std::numeric_limits<T>::min();
    v[1] = std::numeric_limits<T>::max();
  }
  return v;
}

template <class T>
void round_trip(const std::filesystem::path& file, size_t rows, int components) {
  const std::vector<T> values = sample<T>(rows * components);
  {
    H5File h5(file, H5File::Mode::truncate);
    h5.write<T>("/group/sub/data", values, components);
    h5.close();
  }
  H5File h5(file, H5File::Mode::read);
  const H5DatasetInfo info = h5.info("/group/sub/data");
  EXPECT_EQ(info.type, element_type_of<T>());
  EXPECT_EQ(info.rows, rows);
  EXPECT_EQ(info.components, components);
  const std::vector<T> back = h5.read<T>("group/sub/data");
  ASSERT_EQ(back.size(), values.size());
  if (!values.empty()) {  // memcmp must not see the null data() of an empty vector
    EXPECT_EQ(std::memcmp(back.data(), values.data(), values.size() * sizeof(T)), 0)
        << element_type_name(element_type_of<T>()) << " " << rows << " x " << components;
  }
}

template <class T>
void round_trip_all_shapes(const test::TempDir& dir) {
  const auto file = dir / "t.h5";
  round_trip<T>(file, 0, 1);  // empty
  round_trip<T>(file, 0, 3);  // empty, 2-D
  round_trip<T>(file, 7, 1);  // small, contiguous, rank 1
  round_trip<T>(file, 7, 3);  // small, contiguous, rank 2
  // Above the 64 KiB threshold even for u8 (chunked + deflate), with a partial last chunk.
  round_trip<T>(file, 70001, 3);
}

TEST(Hdf5File, EveryElementTypeRoundTripsBitForBit) {
  test::TempDir dir;
  round_trip_all_shapes<double>(dir);
  round_trip_all_shapes<float>(dir);
  round_trip_all_shapes<int64_t>(dir);
  round_trip_all_shapes<int32_t>(dir);
  round_trip_all_shapes<uint32_t>(dir);
  round_trip_all_shapes<uint8_t>(dir);
}

TEST(Hdf5File, LargeDatasetsAreCompressed) {
  test::TempDir dir;
  const auto file = dir / "zeros.h5";
  const std::vector<double> zeros(200000, 0.0);  // 1.6 MB of zeros
  {
    H5File h5(file, H5File::Mode::truncate);
    h5.write<double>("z", zeros);
  }
  // Deflate shrinks runs of zeros by two to three orders of magnitude; 10 % is a loose bound that
  // only an uncompressed (contiguous) dataset fails.
  EXPECT_LT(std::filesystem::file_size(file), zeros.size() * sizeof(double) / 10);
}

TEST(Hdf5File, AttributesRoundTrip) {
  test::TempDir dir;
  const auto file = dir / "attrs.h5";
  const double tricky = std::nextafter(0.1, 1.0);
  {
    H5File h5(file, H5File::Mode::truncate);
    h5.create_groups("/a/b");
    h5.write<int32_t>("/a/b/d", std::vector<int32_t>{1, 2, 3});
    for (const char* obj : {"/", "/a/b", "/a/b/d"}) {
      h5.set_string_attr(obj, "s", "π ≈ 3.14159, \"quoted\"");
      h5.set_string_attr(obj, "empty", "");
      h5.set_double_attr(obj, "x", tricky);
      h5.set_double_attr(obj, "negzero", -0.0);
      h5.set_int_attr(obj, "n", std::numeric_limits<int64_t>::min());
      h5.set_int_attr(obj, "replaced", 1);
      h5.set_int_attr(obj, "replaced", 2);
    }
    h5.close();
  }
  H5File h5(file, H5File::Mode::read);
  for (const char* obj : {"/", "/a/b", "/a/b/d"}) {
    SCOPED_TRACE(obj);
    EXPECT_EQ(h5.string_attr(obj, "s"), "π ≈ 3.14159, \"quoted\"");
    EXPECT_EQ(h5.string_attr(obj, "empty"), "");
    EXPECT_EQ(std::bit_cast<uint64_t>(h5.double_attr(obj, "x")), std::bit_cast<uint64_t>(tricky));
    EXPECT_TRUE(std::signbit(h5.double_attr(obj, "negzero")));
    EXPECT_EQ(h5.int_attr(obj, "n"), std::numeric_limits<int64_t>::min());
    EXPECT_EQ(h5.int_attr(obj, "replaced"), 2);
    EXPECT_DOUBLE_EQ(h5.double_attr(obj, "replaced"), 2.0);  // integers read as doubles
    EXPECT_TRUE(h5.has_attr(obj, "s"));
    EXPECT_FALSE(h5.has_attr(obj, "nope"));
    EXPECT_EQ(h5.attr_names(obj), (std::vector<std::string>{"empty", "n", "negzero", "replaced", "s", "x"}));
  }
  EXPECT_THROW(h5.int_attr("/", "x"), Error);     // a double is not an integer
  EXPECT_THROW(h5.double_attr("/", "s"), Error);  // a string is not a number
  EXPECT_THROW(h5.string_attr("/", "n"), Error);
}

TEST(Hdf5File, StringsGroupsAndListings) {
  test::TempDir dir;
  const auto file = dir / "s.h5";
  const std::string yaml = "scene:\n  name: \"block\"\n  size: [1, 2, 3]\n# ünïcode\n";
  {
    H5File h5(file, H5File::Mode::truncate);
    h5.write_string("/scene", yaml);
    h5.write_string("/nothing", "");
    h5.create_groups("tables/solid_node");
    h5.create_groups("/tables/joint");
    h5.create_groups("/tables/joint");  // existing is fine
    h5.write<uint8_t>("/tables/solid_node/flags", std::vector<uint8_t>{1});
  }
  H5File h5(file, H5File::Mode::read);
  EXPECT_EQ(h5.read_string("/scene"), yaml);
  EXPECT_EQ(h5.read_string("/nothing"), "");
  EXPECT_EQ(h5.children("/"), (std::vector<std::string>{"nothing", "scene", "tables"}));
  EXPECT_EQ(h5.children("/tables"), (std::vector<std::string>{"joint", "solid_node"}));
  EXPECT_TRUE(h5.children("/tables/joint").empty());
  EXPECT_TRUE(h5.exists("/tables/solid_node/flags"));
  EXPECT_FALSE(h5.exists("/tables/fluid/p"));  // missing intermediate level: false, not an error
  EXPECT_TRUE(h5.is_group("/tables"));
  EXPECT_FALSE(h5.is_group("/scene"));
  EXPECT_TRUE(h5.is_dataset("/tables/solid_node/flags"));
  EXPECT_TRUE(h5.exists("/"));
}

using test::error_of;

TEST(Hdf5File, FailuresNameFileAndObject) {
  test::TempDir dir;
  const auto file = dir / "e.h5";
  {
    H5File h5(file, H5File::Mode::truncate);
    h5.write<float>("/f", std::vector<float>{1, 2, 3, 4, 5, 6}, 2);
  }
  H5File h5(file, H5File::Mode::read);
  std::string msg = error_of([&] {
    std::vector<double> out(6);
    h5.read("/f", ElementType::f64, out.data(), 3, 2);
  });
  EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("'/f'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("holds f32, expected f64"), std::string::npos) << msg;

  msg = error_of([&] {
    std::vector<float> out(6);
    h5.read("/f", ElementType::f32, out.data(), 2, 3);
  });
  EXPECT_NE(msg.find("has shape 3 x 2, expected 2 x 3"), std::string::npos) << msg;

  msg = error_of([&] { h5.info("/missing"); });
  EXPECT_NE(msg.find("'/missing'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot open dataset"), std::string::npos) << msg;

  msg = error_of([&] { H5File(dir / "nope.h5", H5File::Mode::read); });
  EXPECT_NE(msg.find("nope.h5"), std::string::npos) << msg;

  std::ofstream(dir / "garbage.h5") << "this is not HDF5";
  msg = error_of([&] { H5File(dir / "garbage.h5", H5File::Mode::read); });
  EXPECT_NE(msg.find("garbage.h5"), std::string::npos) << msg;
  EXPECT_FALSE(is_hdf5_file(dir / "garbage.h5"));
  EXPECT_TRUE(is_hdf5_file(file));
  EXPECT_FALSE(is_hdf5_file(dir / "nope.h5"));
}

TEST(Hdf5File, ElementTypeNamesParse) {
  for (ElementType t : {ElementType::f64, ElementType::f32, ElementType::i64, ElementType::i32,
                        ElementType::u32, ElementType::u8})
    EXPECT_EQ(element_type_from_name(element_type_name(t)), t);
  EXPECT_EQ(element_type_from_name("f16"), std::nullopt);
}

}  // namespace
}  // namespace rift
