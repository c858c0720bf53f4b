// Archard accumulation and the geometry update against closed forms (issue 3 acceptance):
//  - flat-on-flat, uniform pressure p, slip s: volume = k F S sqrt(1 + 3 mu^2) (exactly k F S
//    for mu = 0) and depth = k p s sqrt(1 + 3 mu^2) everywhere;
//  - the Sarkar factor of physics.md section 6 (1.007 at mu 0.07, 1.053 at mu 0.19);
//  - area weighting keeps sum_v depth_v A_v = sum_e depth_e A_e on any triangulation;
//  - receding a flat top vertically by any vertex depth field removes exactly the depth
//    integral sum_v depth_v A_v from the enclosed volume (the linear interpolant's integral);
//  - the inversion counter flags reversed and collapsed faces and nothing else.
// All quantities are exact up to rounding, so the tolerances are rounding tolerances.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <numeric>

#include "engine/state.h"
#include "models/build_model.h"
#include "tests/wear/wear_fixtures.h"
#include "wear/archard.h"
#include "wear/geometry_update.h"
#include "wear/wear_accumulator.h"
#include "wear/wear_loop.h"

using namespace kneesim;

namespace {

constexpr double kLx = 0.040, kLz = 0.030, kH = 0.008;  // box insert [m]

struct FlatSurface {
  models::TriMesh box;
  engine::InsertSurface surface;
  std::vector<int> to_insert, vertex_to_insert;
};

FlatSurface make_flat_surface(int n, double jitter) {
  FlatSurface f;
  f.box = test::make_flat_box(kLx, kLz, kH, n, jitter);
  f.surface = models::make_insert_surface(f.box, 0.0, 0.35, &f.to_insert, &f.vertex_to_insert);
  return f;
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

double sum_area(const std::vector<double>& a) { return std::accumulate(a.begin(), a.end(), 0.0); }

}  // namespace

TEST_CASE("flat box helper: closed, outward, volume lx lz h, top = the articular surface") {
  // reference: the box's own dimensions; the helper must be right before it proves anything
  for (double jitter : {0.0, 0.3}) {
    const FlatSurface f = make_flat_surface(8, jitter);
    const models::MeshCheck c = models::check_mesh(f.box);
    CHECK(c.watertight());
    CHECK(rel(models::enclosed_volume(f.box), kLx * kLz * kH) < 1e-12);
    CHECK(f.surface.size() == 2 * 8 * 8);
    CHECK(rel(sum_area(f.surface.area), kLx * kLz) < 1e-12);
  }
}

TEST_CASE("Sarkar factor sqrt(1 + 3 mu^2): physics.md section 6 values") {
  // closed form: sqrt(1.0147) = 1.00733, sqrt(1.1083) = 1.05276; physics.md prints them to
  // 3 decimals (1.007, 1.053), so those are checked to half a unit of the last digit
  CHECK(wear::sarkar_factor(0.07) == doctest::Approx(1.00733).epsilon(1e-4));
  CHECK(wear::sarkar_factor(0.19) == doctest::Approx(1.0527).epsilon(1e-4));
  CHECK(std::abs(wear::sarkar_factor(0.07) - 1.007) < 5e-4);
  CHECK(std::abs(wear::sarkar_factor(0.19) - 1.053) < 5e-4);
  CHECK(wear::sarkar_factor(0.0) == 1.0);  // frictionless: plain Archard, exactly
  // the increment is the product k p ds times the factor (units: m^2/N * Pa * m = m):
  // 2e-16 * 1e7 * 1e-3 = 2e-12 m, times sqrt(1.0147) = 1.007323185
  CHECK(wear::archard_increment(2e-16, 1e7, 1e-3, 0.07) ==
        doctest::Approx(2.0146463710e-12).epsilon(1e-10).scale(0));
}

TEST_CASE("flat on flat, uniform pressure: volume k F S (Sarkar-corrected), depth k p s") {
  // reference: Archard (1953) with the Sarkar correction, physics.md section 6. A flat insert
  // of area A under uniform pressure p sliding at v for N steps of dt carries F = p A over
  // S = N v dt, so V = k F S sqrt(1 + 3 mu^2) and h = k p S sqrt(1 + 3 mu^2) at every point.
  // Exact by construction: tolerance 1e-12 relative (sums of N equal terms round at ~1e-14).
  const double p = 5e6, v = 0.05, dt = 1e-3;  // 5 MPa, 50 mm/s, 1 ms
  const int steps = 1000;                      // S = 50 mm
  const double k = 2.643e-10 * wear::kWearFactorSI;
  // the Sarkar factor sqrt(1 + 3 mu^2) at mu = 0, 0.07, 0.19, tabulated (values above)
  const std::map<double, double> kSarkar = {{0.0, 1.0}, {0.07, 1.007323185477}, {0.19, 1.052758281848}};
  for (double jitter : {0.0, 0.35}) {
    for (double mu : {0.0, 0.07, 0.19}) {
      CAPTURE(jitter);
      CAPTURE(mu);
      const FlatSurface f = make_flat_surface(10, jitter);
      engine::Model model;
      model.dt = dt;
      model.insert = f.surface;
      const engine::State state;
      const engine::Data data = test::make_uniform_contact(f.surface, p, v);
      wear::WearLawParams law;
      law.wear_factor = k;
      law.friction = mu;
      wear::WearAccumulator acc(f.surface.size(), law);
      for (int i = 0; i < steps; ++i) acc.observe(model, state, data);

      const double area = sum_area(f.surface.area);
      const double F = p * area, S = steps * v * dt;
      const double sarkar = kSarkar.at(mu);
      const std::vector<double> elem = acc.depth_per_cycle();
      const std::vector<double> vdepth = wear::spread_to_vertices(f.surface, elem);
      const std::vector<double> varea = wear::vertex_areas(f.surface);
      REQUIRE(vdepth.size() == f.surface.vertices_T.size());
      double volume = 0.0;
      for (size_t i = 0; i < vdepth.size(); ++i) volume += vdepth[i] * varea[i];
      CHECK(rel(sum_area(varea), area) < 1e-12);  // tributary areas tile the surface
      CHECK(rel(volume, k * F * S * sarkar) < 1e-12);
      if (mu == 0.0) CHECK(rel(volume, k * F * S) < 1e-12);
      double worst = 0.0;
      for (double d : vdepth) worst = std::max(worst, rel(d, k * p * S * sarkar));
      for (double d : elem) worst = std::max(worst, rel(d, k * p * S * sarkar));
      CHECK(worst < 1e-12);
      CHECK(rel(acc.sliding_work(), F * S) < 1e-12);  // frictional path work p A ds
      // unidirectional sliding along x: no cross-shear
      for (double cs : acc.cross_shear_ratio()) CHECK(cs == doctest::Approx(0.0).epsilon(1e-15));
    }
  }
}

TEST_CASE("pressure-dependent and cross-shear laws: closed forms on the flat surface") {
  // references (physics.md section 6 extensions, wear/wear_accumulator.h):
  //  - Mazzucco & Spector 2003 form k = k_ref (p / p_ref)^-alpha: at p = p_ref / 2 and
  //    alpha = 0.5 the depth is sqrt(2) times the Archard depth;
  //  - cross-shear CS = smallest / total principal frictional work (Kang 2008): equal work along
  //    x then along z gives CS = 1/2, so k = k_ref (1 + beta / 2); sliding along one fixed
  //    oblique direction (x = z) is unidirectional, CS = 0 and k = k_ref.
  // Tolerance 1e-12 relative: closed forms evaluated in floating point.
  const FlatSurface f = make_flat_surface(3, 0.0);
  engine::Model model;
  model.dt = 1e-3;
  model.insert = f.surface;
  const double p = 5e6, v = 0.02, k = 1e-16;
  const int steps = 200;
  const double archard = k * p * steps * v * model.dt * wear::sarkar_factor(0.07);

  wear::WearLawParams pd;
  pd.law = wear::WearLaw::kPressureDependent;
  pd.wear_factor = k;
  pd.p_ref = 2.0 * p;
  pd.alpha = 0.5;
  wear::WearAccumulator a(f.surface.size(), pd);
  const engine::Data data_x = test::make_uniform_contact(f.surface, p, v);
  for (int i = 0; i < steps; ++i) a.observe(model, engine::State{}, data_x);
  for (double d : a.depth_per_cycle()) CHECK(rel(d, std::sqrt(2.0) * archard) < 1e-12);

  wear::WearLawParams cs;
  cs.law = wear::WearLaw::kCrossShear;
  cs.wear_factor = k;
  cs.beta = 3.0;
  wear::WearAccumulator b(f.surface.size(), cs);
  engine::Data data_z = data_x;
  for (auto& u : data_z.slip_velocity_T) u = Eigen::Vector3d(0.0, 0.0, v);
  for (int i = 0; i < steps / 2; ++i) b.observe(model, engine::State{}, data_x);
  for (int i = 0; i < steps / 2; ++i) b.observe(model, engine::State{}, data_z);
  for (double r : b.cross_shear_ratio()) CHECK(r == doctest::Approx(0.5).epsilon(1e-12));
  for (double d : b.depth_per_cycle()) CHECK(rel(d, (1.0 + 0.5 * cs.beta) * archard) < 1e-12);

  wear::WearAccumulator c(f.surface.size(), cs);
  engine::Data data_xz = data_x;
  for (auto& u : data_xz.slip_velocity_T) u = Eigen::Vector3d(v, 0.0, v) / std::sqrt(2.0);
  for (int i = 0; i < steps; ++i) c.observe(model, engine::State{}, data_xz);
  for (double r : c.cross_shear_ratio()) CHECK(std::abs(r) < 1e-12);
  for (double d : c.depth_per_cycle()) CHECK(rel(d, archard) < 1e-12);
}

TEST_CASE("only elements in contact with p > 0 and slip wear") {
  // reference: Archard's law has no wear without load or without sliding
  const FlatSurface f = make_flat_surface(4, 0.0);
  engine::Model model;
  model.dt = 1e-3;
  model.insert = f.surface;
  engine::Data data = test::make_uniform_contact(f.surface, 2e6, 0.1);
  data.in_contact = {0, 1, 2};
  data.pressure[1] = 0.0;    // in the list but unloaded
  data.slip_speed[2] = 0.0;  // loaded but sticking
  wear::WearLawParams law;
  law.wear_factor = 1e-16;
  wear::WearAccumulator acc(f.surface.size(), law);
  acc.observe(model, engine::State{}, data);
  const std::vector<double> d = acc.depth_per_cycle();
  CHECK(d[0] ==
        doctest::Approx(1e-16 * 2e6 * 1e-4 * wear::sarkar_factor(0.07)).epsilon(1e-14).scale(0));
  for (size_t e = 1; e < d.size(); ++e) CHECK(d[e] == 0.0);
}

TEST_CASE("area weighting keeps the volume: sum_v depth_v A_v = sum_e depth_e A_e") {
  // reference: the invariant wear/geometry_update.h promises, on an irregular triangulation
  // with an arbitrary element depth field; tolerance: rounding of sums over ~500 terms
  const FlatSurface f = make_flat_surface(16, 0.4);
  std::vector<double> elem(f.surface.size());
  double expected = 0.0;
  for (int e = 0; e < f.surface.size(); ++e) {
    const Eigen::Vector3d& c = f.surface.centroid_T[e];
    elem[e] = 1e-5 * (1.0 + std::sin(200.0 * c.x()) * std::cos(150.0 * c.z()));
    expected += elem[e] * f.surface.area[e];
  }
  const std::vector<double> vdepth = wear::spread_to_vertices(f.surface, elem);
  const std::vector<double> varea = wear::vertex_areas(f.surface);
  double volume = 0.0;
  for (size_t i = 0; i < vdepth.size(); ++i) volume += vdepth[i] * varea[i];
  CHECK(rel(volume, expected) < 1e-12);
}

TEST_CASE("receding a flat top removes exactly the depth integral from the enclosed volume") {
  // reference: a planar top moved straight down by a piecewise-linear depth field loses
  // sum_t A_t (d1 + d2 + d3) / 3 = sum_v d_v A_v of volume (the integral of the linear
  // interpolant), whatever the triangulation; the flat top's vertex normals are exactly +y.
  // Tolerance 1e-9 relative: the enclosed volume (9600 mm^3) is a sum of signed tetrahedra
  // rounding at ~1e-16 of the total, i.e. ~1e-12 of a 1 mm^3-scale loss.
  const FlatSurface f = make_flat_surface(12, 0.3);
  const std::vector<Eigen::Vector3d> normals = wear::articular_vertex_normals(f.surface);
  for (const auto& n : normals) CHECK((n - Eigen::Vector3d::UnitY()).norm() < 1e-15);
  std::vector<double> depth(f.surface.vertices_T.size());
  for (size_t v = 0; v < depth.size(); ++v) {
    const Eigen::Vector3d& p = f.surface.vertices_T[v];
    depth[v] = 2e-4 * (1.0 + p.x() / kLx) * (1.0 + 0.5 * std::cos(100.0 * p.z()));  // 0.05-0.3 mm
  }
  const std::vector<double> varea = wear::vertex_areas(f.surface);
  double integral = 0.0;
  for (size_t v = 0; v < depth.size(); ++v) integral += depth[v] * varea[v];
  const wear::RecessionResult r = wear::recede(f.box, f.vertex_to_insert, normals, depth);
  CHECK(r.inverted_faces == 0);
  CHECK(models::check_mesh(r.insert).watertight());
  const double loss = models::enclosed_volume(f.box) - models::enclosed_volume(r.insert);
  CHECK(rel(loss, integral) < 1e-9);
  // and the worn model surface follows the moved vertices
  models::BuiltModel built;
  built.model.insert = f.surface;
  built.implant.insert = f.box;
  built.implant.articular_to_insert = f.to_insert;
  built.implant.articular_vertex_to_insert = f.vertex_to_insert;
  const engine::InsertSurface worn = models::make_worn_insert_surface(built, r.insert);
  for (size_t v = 0; v < depth.size(); ++v) {
    CHECK(worn.vertices_T[v].y() == doctest::Approx(kH - depth[v]).epsilon(1e-12));
  }
}

TEST_CASE("inverted-face counter: reversed or collapsed faces, nothing else") {
  // reference: the definition in wear/geometry_update.h (normal reversed, or area below 1 %)
  models::TriMesh before;
  before.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  before.triangles = {{0, 1, 2}};
  models::TriMesh after = before;
  after.vertices[2] = {0.2, 0.5, 0.3};  // tilted, shrunk to 50 %: still fine
  CHECK(wear::count_inverted_faces(before, after) == 0);
  after.vertices[2] = {0.0, -1.0, 0.0};  // reversed
  CHECK(wear::count_inverted_faces(before, after) == 1);
  after.vertices[2] = {0.0, 0.005, 0.0};  // 0.5 % of the area: collapsed
  CHECK(wear::count_inverted_faces(before, after) == 1);
  // a recession deeper than the box at one top vertex turns its wall faces inside out
  const FlatSurface f = make_flat_surface(4, 0.0);
  std::vector<double> depth(f.surface.vertices_T.size(), 0.0);
  int corner = -1;  // an articular vertex on the box's edge (it carries wall faces)
  for (size_t v = 0; v < depth.size(); ++v)
    if (std::abs(f.surface.vertices_T[v].x() + 0.5 * kLx) < 1e-12) corner = static_cast<int>(v);
  REQUIRE(corner >= 0);
  depth[corner] = 2.0 * kH;
  const wear::RecessionResult r =
      wear::recede(f.box, f.vertex_to_insert, wear::articular_vertex_normals(f.surface), depth);
  CHECK(r.inverted_faces > 0);
}

TEST_CASE("update schedule: the list in order, its last entry repeated; else update_every") {
  wear::WearOptions o;
  o.update_every = 250'000;
  CHECK(wear::update_interval(o, 0) == 250'000);
  CHECK(wear::update_interval(o, 7) == 250'000);
  o.schedule = {50'000, 100'000, 250'000};
  CHECK(wear::update_interval(o, 0) == 50'000);
  CHECK(wear::update_interval(o, 1) == 100'000);
  CHECK(wear::update_interval(o, 2) == 250'000);
  CHECK(wear::update_interval(o, 9) == 250'000);
}

TEST_CASE("effective cycles of running-in and incubation: additive over updates, closed limits") {
  // reference: the integral of the rate factor over [n0, n0 + n] is additive over consecutive
  // intervals (the wear loop splits a run into updates), and its limits are the steady line
  // shifted by +a N_r (running-in) or -N_i (incubation)
  wear::WearLawParams run_in;
  run_in.law = wear::WearLaw::kRunningIn;
  run_in.running_in_excess = 0.5;
  run_in.running_in_cycles = 2e5;
  wear::WearLawParams incub;
  incub.law = wear::WearLaw::kIncubation;
  incub.incubation_cycles = 1.5e5;
  for (const auto& law : {run_in, incub}) {
    const double whole = wear::effective_cycles(law, 0.0, 3e6);
    const double split = wear::effective_cycles(law, 0.0, 2.5e5) +
                         wear::effective_cycles(law, 2.5e5, 7.5e5) +
                         wear::effective_cycles(law, 1e6, 2e6);
    CHECK(split == doctest::Approx(whole).epsilon(1e-12));
  }
  CHECK(wear::effective_cycles(run_in, 0.0, 1e8) == doctest::Approx(1e8 + 0.5 * 2e5).epsilon(1e-12));
  CHECK(wear::effective_cycles(incub, 0.0, 1e8) == doctest::Approx(1e8 - 1.5e5).epsilon(1e-12));
  // the incubation rate starts at zero: the first 100 cycles count as 100^2 / (2 N_i)
  CHECK(wear::effective_cycles(incub, 0.0, 100.0) ==
        doctest::Approx(100.0 * 100.0 / (2.0 * 1.5e5)).epsilon(1e-3));
}
