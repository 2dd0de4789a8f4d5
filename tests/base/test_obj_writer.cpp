// Tests of base/obj_writer: the text is exactly what printf's "%.17g" (vertices), "%.9g"
// (normals) and "%lld" (1-based indices) give, the format every OBJ thaw wrote so far has
// (resumed runs compare kept files byte for byte), whatever the conversion routine.
#include "base/obj_writer.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace thaw::meshio {
namespace {

std::string printf_line(const char* format, double a, double b, double c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

TEST(FormatObj, NumbersAreWhatPrintfWrites) {
  // Values where the two conversions could part: exponent switches of %g (1e-5, 1e16, 1e17),
  // ties, zeros of both signs, the extremes, subnormals, and many random bit patterns.
  std::vector<double> values = {0.0,      -0.0, 1.0,    0.1,    1e-4,        1e-5,
                                9.99e-5,  1e16, 1e17,   5e-324, DBL_MIN,     DBL_MAX,
                                -DBL_MAX, 0.5,  2.5e-8, 0.03,   123456789.0, 1.0 / 3.0};
  std::mt19937_64 bits(7);
  while (values.size() < 30000) {
    const std::uint64_t u = bits();
    double x = 0;
    std::memcpy(&x, &u, sizeof x);
    if (std::isfinite(x)) values.push_back(x);
    values.push_back(std::ldexp(static_cast<double>(bits() % 1000000007) / 1e9 - 0.5,
                                static_cast<int>(bits() % 60) - 40));
  }
  TriangleMesh m;
  std::string expect;
  for (std::size_t i = 0; i + 2 < values.size(); i += 3) {
    m.vertices.push_back({values[i], values[i + 1], values[i + 2]});
    expect += printf_line("v %.17g %.17g %.17g\n", values[i], values[i + 1], values[i + 2]);
  }
  for (std::size_t i = 0; i + 2 < values.size(); i += 3) {
    m.normals.push_back({values[i + 2], values[i], values[i + 1]});
    expect += printf_line("vn %.9g %.9g %.9g\n", values[i + 2], values[i], values[i + 1]);
  }
  const std::int64_t big = std::numeric_limits<std::int64_t>::max() - 1;
  m.triangles = {{0, 1, 2}, {big, 9, 99999}};
  m.normal_triangles = {{2, 0, 1}, {1, big, 12345}};
  char buf[256];
  std::snprintf(buf, sizeof buf, "f %lld//%lld %lld//%lld %lld//%lld\n", 1LL, 3LL, 2LL, 1LL, 3LL,
                2LL);
  expect += buf;
  std::snprintf(buf, sizeof buf, "f %lld//%lld %lld//%lld %lld//%lld\n",
                static_cast<long long>(big) + 1, 2LL, 10LL, static_cast<long long>(big) + 1,
                100000LL, 12346LL);
  expect += buf;
  EXPECT_EQ(format_obj(m, "c"), "# c\n" + expect);
  // Without normals: "f a b c".
  m.normals.clear();
  m.normal_triangles.clear();
  m.vertices.resize(1);
  m.triangles = {{0, 0, 0}};
  EXPECT_EQ(format_obj(m, ""),
            printf_line("v %.17g %.17g %.17g\n", values[0], values[1], values[2]) + "f 1 1 1\n");
  // Into a buffer that held a longer text: replaced, nothing of it left.
  std::string reused = "# stale\n" + expect + expect;
  format_obj(m, "", reused);
  EXPECT_EQ(reused, format_obj(m, ""));
}

}  // namespace
}  // namespace thaw::meshio
