// References: synthetic fields with known connected regions (counted by hand), the
// equivalent-radius definition R = (3V/4pi)^(1/3) of the particle-size study, and the
// height-map format's error messages.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "engine/errors.h"
#include "wear/particles/detachment.h"
#include "wear/particles/height_map.h"

using namespace kneesim::particles;

TEST_CASE("labelling: surface-reaching regions only, 6-connectivity, periodic seam") {
  Grid g{8, 8, 1e-7, 1e-7, true};
  const int nz = 4;
  std::vector<double> vm(nz * g.size(), 0.0);
  auto set = [&](int i, int j, int l) { vm[l * g.size() + i * g.ny + j] = 2.0; };
  // A: a 2 x 2 x 3 block at the surface
  for (int i = 1; i < 3; ++i)
    for (int j = 1; j < 3; ++j)
      for (int l = 0; l < 3; ++l) set(i, j, l);
  // B: buried, touches A only diagonally -> separate and not at the surface
  set(3, 3, 3);
  // C: across the periodic seam in y: cells j = 7 and j = 0 at i = 6, surface level
  set(6, 7, 0);
  set(6, 0, 0);
  // D: diagonal neighbours at the surface are two regions under 6-connectivity
  set(4, 5, 0);
  set(5, 6, 0);
  const Detachment d = find_particles(vm, g, nz, 1e-7, 1.0);
  REQUIRE(d.particles.size() == 4);  // A, D1, D2, C (B is buried)
  const Particle& a = d.particles[0];
  CHECK(a.volume == doctest::Approx(12 * 1e-21).scale(0));
  CHECK(a.eq_radius == doctest::Approx(std::cbrt(3 * 12e-21 / (4 * M_PI))).scale(0));
  CHECK(a.length == doctest::Approx(2e-7).scale(0));
  CHECK(a.width == doctest::Approx(2e-7).scale(0));
  CHECK(a.thickness == doctest::Approx(3e-7).scale(0));
  const Particle& c = d.particles[3];
  CHECK(c.width == doctest::Approx(2e-7).scale(0));  // followed across the seam
  CHECK(d.removed_depth[1 * g.ny + 1] == doctest::Approx(3e-7).scale(0));
  CHECK(d.removed_depth[3 * g.ny + 3] == 0.0);
  // without periodicity the seam splits C in two
  g.periodic_y = false;
  CHECK(find_particles(vm, g, nz, 1e-7, 1.0).particles.size() == 5);
}

TEST_CASE("height map import and its errors") {
  const auto dir = std::filesystem::temp_directory_path() / "kneesim_particles_test";
  std::filesystem::create_directories(dir);
  const auto good = dir / "good.csv";
  {
    std::ofstream f(good);
    f << "# test map\nspacing_nm,100\n1,2\n3,4\n";
  }
  const HeightMap m = read_height_map(good);
  CHECK(m.grid.nx == 2);
  CHECK(m.grid.ny == 2);
  CHECK(m.grid.dx == doctest::Approx(1e-7).scale(0));
  CHECK(m.height[3] == doctest::Approx(1.5e-9).scale(0));
  const auto ragged = dir / "ragged.csv";
  {
    std::ofstream f(ragged);
    f << "spacing_nm,100\n1,2\n3\n";
  }
  try {
    read_height_map(ragged);
    FAIL("ragged rows accepted");
  } catch (const kneesim::InputError& e) {
    CHECK(std::string(e.what()).find("row 2") != std::string::npos);
  }
  const auto zero = dir / "zero.csv";
  {
    std::ofstream f(zero);
    f << "spacing_nm,0\n1,2\n3,4\n";
  }
  CHECK_THROWS_AS(read_height_map(zero), kneesim::InputError);
  std::filesystem::remove_all(dir);
}
