// The .vtp writer's number formatting (engine/io/vtp.cpp, std::to_chars) against its
// reference, printf's "%.9g" and "%d", which it replaced: the same text for values of every
// magnitude, sign, zeros, subnormals, integers and non-finite values.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "engine/io/vtp.h"

namespace {

std::string g9(double v, const char* after) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g%s", v, after);
  return buf;
}

}  // namespace

TEST_CASE("vtp numbers are printf's %.9g and %d") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-320, 308);
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.1, 1e-5, 123456789.0, 1234567891.0,
                                5e-324, std::numeric_limits<double>::max(), 0.5e-4, 1e16,
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN()};
  for (int i = 0; i < 20000; ++i) values.push_back(std::ldexp(mantissa(rng), exponent(rng) / 4));
  for (int i = 0; i < 20000; ++i) values.push_back(std::ldexp(mantissa(rng), exponent(rng)));
  kneesim::io::VtpSurface s;
  for (size_t i = 0; i + 2 < values.size(); i += 3) {
    s.points_mm.emplace_back(values[i], values[i + 1], values[i + 2]);
  }
  std::uniform_int_distribution<int> index(-2147483647 - 1, 2147483647);
  for (int i = 0; i < 1000; ++i) s.triangles.emplace_back(index(rng), i, -i);
  kneesim::io::VtpArray a{"v", {}};
  for (size_t i = 0; i < s.points_mm.size(); ++i) a.values.push_back(values[i]);
  s.point_data.push_back(a);
  std::string points, triangles, array;
  for (const auto& p : s.points_mm) points += g9(p.x(), " ") + g9(p.y(), " ") + g9(p.z(), "\n");
  for (const auto& t : s.triangles) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%d %d %d\n", t.x(), t.y(), t.z());
    triangles += buf;
  }
  for (double v : a.values) array += g9(v, " ");
  const std::string text = kneesim::io::format_vtp(s);
  CHECK(text.find(points) != std::string::npos);
  CHECK(text.find(triangles) != std::string::npos);
  CHECK(text.find(array) != std::string::npos);
}
