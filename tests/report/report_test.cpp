// The report's kernels (analysis/report) against independent references: SHA-256 and base64
// against their standards' test vectors, the colour quantisation of a scene field by hand, the
// SVG plot's axes and escaping.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "analysis/report/file_hash.h"
#include "analysis/report/scene3d.h"
#include "analysis/report/svg_plot.h"

using namespace kneesim::report;

TEST_CASE("sha256 of the FIPS 180-2 examples") {
  CHECK(sha256_text("abc") ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_text("") ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_file("/nonexistent/file").empty());
}

TEST_CASE("base64 of the RFC 4648 test vectors") {
  const char* in[] = {"", "f", "fo", "foo", "foob", "fooba", "foobar"};
  const char* out[] = {"", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy"};
  for (int i = 0; i < 7; ++i) CHECK(base64(in[i], std::string(in[i]).size()) == out[i]);
}

TEST_CASE("nice ticks cover the range with 1-2-5 steps") {
  const auto t = nice_ticks(-5.3, 6.8);
  CHECK(t.front() <= -5.3);
  CHECK(t.back() >= 6.8);
  CHECK(t[1] - t[0] == doctest::Approx(5.0));  // (6.8 + 5.3) / 5 = 2.4 -> the next of 1, 2, 5
  CHECK(t.size() == 5);                         // -10, -5, 0, 5, 10
  CHECK(nice_ticks(0.0, 0.9)[1] == doctest::Approx(0.2));
  const auto u = nice_ticks(3.0, 3.0);  // a constant series still gets an axis
  CHECK(u.size() >= 2);
  CHECK(u.front() < u.back());
}

TEST_CASE("a scene field is quantised to 0..254 of [0, max], 255 off the surface") {
  Scene3D s;
  s.insert.vertices_mm = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  s.insert.triangles = {{0, 1, 2}, {1, 3, 2}, {0, 2, 3}};
  s.step_values = {0, 50};
  const double nan = std::nan("");
  s.fields.push_back({"p", "MPa", {{nan, 0.0, 10.0}, {nan, 5.0, 2.0}}});
  const nlohmann::json j = scene_json(s);
  const auto& f = j["fields"][0];
  CHECK(f["max"].get<double>() == 10.0);
  CHECK(f["min"].get<double>() == 0.0);
  CHECK(f["face_count"].get<int>() == 2);  // face 0 never has a value: not stored
  // faces 1, 2 as uint32 LE; values step 0: 0, 254; step 1: 127, 51 (5/10, 2/10 of 254)
  const uint32_t faces[] = {1, 2};
  CHECK(f["faces"] == base64(faces, sizeof faces));
  const unsigned char q[] = {0, 254, 127, 51};
  CHECK(f["values"] == base64(q, 4));
  CHECK(f["step_max"][1].get<double>() == 5.0);
  s.fields[0].steps.pop_back();
  CHECK_THROWS_AS(scene_json(s), std::logic_error);  // a field must have every step
}

TEST_CASE("an SVG plot carries its labels, escaped, and skips non-finite points") {
  PlotSpec p;
  p.title = "AP <translation>";
  p.x_label = "gait cycle (%)";
  p.y_label = "AP, tibia anterior (mm)";
  p.series.push_back({"a", {0, 1, 2}, {0, std::nan(""), 2}, "", false, false});
  const std::string svg = svg_line_plot(p);
  CHECK(svg.find("AP &lt;translation&gt;") != std::string::npos);
  CHECK(svg.find("AP, tibia anterior (mm)") != std::string::npos);
  CHECK(svg.find("nan") == std::string::npos);
  // two finite points: two coordinate pairs in the polyline
  const auto a = svg.find("points=\""), b = svg.find('"', a + 8);
  const std::string pts = svg.substr(a + 8, b - a - 8);
  CHECK(std::count(pts.begin(), pts.end(), ',') == 2);
}
