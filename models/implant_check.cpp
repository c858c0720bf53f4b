#include "models/implant_check.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <mutex>
#include <set>
#include <numbers>

#include "engine/errors.h"

namespace kneesim::models {
namespace {

constexpr double kMm = 1e-3;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// thresholds of the checks [mm] and why
constexpr double kFlatNormal = 0.99;     // a face this close to horizontal is "flat"
constexpr double kFlatBand_mm = 0.5;     // flat faces within this of the bottom / top
constexpr double kMinArcRadius_mm = 10;  // a distal condylar arc is 20-60 mm; a flange tip ~2
constexpr double kMaxArcRadius_mm = 200;  // an insert's flat base given as the femur: ~infinite
constexpr double kArcSlice_mm = 1.5;     // half width of the sagittal slice
constexpr double kArcDepth_mm = 6.0;     // height of the distal profile fitted
constexpr int kMinArcPoints = 8;
constexpr double kAxisMargin_mm = 10.0;  // the axis may lie this far outside the femur's box
constexpr double kAxisAboveLowest_mm = 5.0;  // and at least this far above its lowest point
constexpr double kAxisWarn_mm = 2.0;     // axis this far from the arcs' centre: a warning
constexpr double kBaseWarn_mm = 0.5;     // insert's lowest point this far from the base plane
constexpr double kStartPlacement_mm = 1.0;  // build_model: femur 1 mm above the insert's top

std::string config_name(const Config& c) {
  return c.file.empty() ? std::string("built-in config") : c.file.string();
}

std::string fmt(const char* format, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

std::string vec_mm(const Eigen::Vector3d& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.1f, %.1f, %.1f]", v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);
  return buf;
}

std::string vec_mm(const std::array<double, 3>& v) {
  return vec_mm(Eigen::Vector3d(v[0], v[1], v[2]));
}

bool same_file_bytes(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;
  const auto sa = std::filesystem::file_size(a, ec);
  if (ec) return false;
  const auto sb = std::filesystem::file_size(b, ec);
  if (ec || sa != sb) return false;
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  return std::equal(std::istreambuf_iterator<char>(fa), std::istreambuf_iterator<char>(),
                    std::istreambuf_iterator<char>(fb));
}

// the same shape up to a translation (the femur is shifted by its origin, the insert by its
// base): e.g. one mesh saved twice in two formats
bool same_shape(const TriMesh& a, const TriMesh& b) {
  if (a.vertices.size() != b.vertices.size() || a.triangles.size() != b.triangles.size() ||
      a.vertices.empty()) {
    return false;
  }
  const Eigen::Vector3d da = a.vertices[0], db = b.vertices[0];
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    if (((a.vertices[i] - da) - (b.vertices[i] - db)).norm() > 1e-9) return false;
  }
  return true;
}

// flat area facing down at the bottom and facing up at the top of a mesh [m^2]
struct FlatAreas {
  double bottom = 0.0, top = 0.0;
};

FlatAreas find_flat_areas(const TriMesh& m) {
  const auto box = bounding_box(m);
  const auto normals = face_normals(m);
  const auto areas = face_areas(m);
  FlatAreas f;
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    const double cy = (m.vertices[t[0]].y() + m.vertices[t[1]].y() + m.vertices[t[2]].y()) / 3;
    if (normals[i].y() < -kFlatNormal && cy < box.min().y() + kFlatBand_mm * kMm) {
      f.bottom += areas[i];
    }
    if (normals[i].y() > kFlatNormal && cy > box.max().y() - kFlatBand_mm * kMm) f.top += areas[i];
  }
  return f;
}

// algebraic (Kasa) circle fit to the sagittal profile through the condyle's lowest point
CondyleArc fit_condyle_arc(const TriMesh& femur, int side) {
  CondyleArc arc;
  const Eigen::Vector3d* low = nullptr;
  for (const auto& v : femur.vertices) {
    if (side * v.z() > 5.0 * kMm && (!low || v.y() < low->y())) low = &v;
  }
  if (!low) return arc;
  std::vector<Eigen::Vector2d> pts;
  for (const auto& v : femur.vertices) {
    if (std::abs(v.z() - low->z()) < kArcSlice_mm * kMm && v.y() < low->y() + kArcDepth_mm * kMm) {
      pts.emplace_back(v.x() / kMm, v.y() / kMm);
    }
  }
  arc.z_mm = low->z() / kMm;
  arc.points = static_cast<int>(pts.size());
  if (arc.points < kMinArcPoints) return arc;
  // x^2 + y^2 = 2 a x + 2 b y + c, centred on the points' mean for conditioning
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= pts.size();
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd rhs(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d p = pts[i] - mean;
    A.row(i) << 2 * p.x(), 2 * p.y(), 1.0;
    rhs[i] = p.squaredNorm();
  }
  const Eigen::Vector3d s = A.colPivHouseholderQr().solve(rhs);
  const double r2 = s[2] + s[0] * s[0] + s[1] * s[1];
  if (!(r2 > 0.0)) return arc;
  arc.found = true;
  arc.x_mm = s[0] + mean.x();
  arc.y_mm = s[1] + mean.y();
  arc.radius_mm = std::sqrt(r2);
  double sum = 0.0;
  for (const auto& p : pts) {
    const double d = (p - Eigen::Vector2d(arc.x_mm, arc.y_mm)).norm() - arc.radius_mm;
    sum += d * d;
  }
  arc.rms_mm = std::sqrt(sum / pts.size());
  return arc;
}

// the insert's articular faces as make_insert_surface selects them
std::vector<int> articular_faces(const TriMesh& insert, double min_normal_y) {
  const auto normals = face_normals(insert);
  const auto areas = face_areas(insert);
  std::vector<int> out;
  for (size_t f = 0; f < insert.triangles.size(); ++f) {
    const auto& t = insert.triangles[f];
    const double cy =
        (insert.vertices[t[0]].y() + insert.vertices[t[1]].y() + insert.vertices[t[2]].y()) / 3;
    if (normals[f].y() > min_normal_y && cy > 1e-4 && areas[f] > 0.0) {
      out.push_back(static_cast<int>(f));
    }
  }
  return out;
}

// the highest articular surface over each cell of an x-z grid (T frame), for gaps
class HeightMap {
 public:
  HeightMap(const TriMesh& insert, const std::vector<int>& faces, double cell)
      : cell_(cell) {
    lo_ = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d hi = -lo_;
    for (int f : faces) {
      for (int k = 0; k < 3; ++k) {
        const auto& v = insert.vertices[insert.triangles[f][k]];
        lo_ = lo_.cwiseMin(Eigen::Vector2d(v.x(), v.z()));
        hi = hi.cwiseMax(Eigen::Vector2d(v.x(), v.z()));
      }
    }
    if (faces.empty()) return;
    nx_ = static_cast<int>(std::ceil((hi.x() - lo_.x()) / cell_)) + 1;
    nz_ = static_cast<int>(std::ceil((hi.y() - lo_.y()) / cell_)) + 1;
    h_.assign(static_cast<size_t>(nx_) * nz_, -std::numeric_limits<double>::infinity());
    for (int f : faces) {
      const auto& a = insert.vertices[insert.triangles[f][0]];
      const auto& b = insert.vertices[insert.triangles[f][1]];
      const auto& c = insert.vertices[insert.triangles[f][2]];
      const double x0 = std::min({a.x(), b.x(), c.x()}), x1 = std::max({a.x(), b.x(), c.x()});
      const double z0 = std::min({a.z(), b.z(), c.z()}), z1 = std::max({a.z(), b.z(), c.z()});
      const double det = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
      if (std::abs(det) < 1e-18) continue;
      for (int i = index(x0, lo_.x()); i <= index(x1, lo_.x()); ++i) {
        for (int j = index(z0, lo_.y()); j <= index(z1, lo_.y()); ++j) {
          const double x = lo_.x() + (i + 0.5) * cell_, z = lo_.y() + (j + 0.5) * cell_;
          const double u = ((x - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (z - a.z())) / det;
          const double v = ((b.x() - a.x()) * (z - a.z()) - (x - a.x()) * (b.z() - a.z())) / det;
          if (u < -1e-9 || v < -1e-9 || u + v > 1 + 1e-9) continue;
          if (i < 0 || j < 0 || i >= nx_ || j >= nz_) continue;
          const double y = a.y() + u * (b.y() - a.y()) + v * (c.y() - a.y());
          double& h = h_[static_cast<size_t>(i) * nz_ + j];
          h = std::max(h, y);
        }
      }
    }
  }

  // the articular surface height under (x, z), or -inf outside it
  double at(double x, double z) const {
    if (h_.empty()) return -std::numeric_limits<double>::infinity();
    const int i = index(x, lo_.x()), j = index(z, lo_.y());
    if (i < 0 || j < 0 || i >= nx_ || j >= nz_) return -std::numeric_limits<double>::infinity();
    return h_[static_cast<size_t>(i) * nz_ + j];
  }

 private:
  int index(double v, double lo) const { return static_cast<int>(std::floor((v - lo) / cell_)); }
  double cell_;
  Eigen::Vector2d lo_;
  int nx_ = 0, nz_ = 0;
  std::vector<double> h_;
};

// smallest vertical gap of the femur (its vertices shifted by `shift`, T frame) over the
// articular surface, among vertices with side * z >= 0 (side 0: all) [m]; NaN over nothing
double find_gap(const TriMesh& femur, const Eigen::Vector3d& shift, const HeightMap& h,
                int side) {
  double gap = std::numeric_limits<double>::infinity();
  for (const auto& v0 : femur.vertices) {
    const Eigen::Vector3d v = v0 + shift;
    if (side != 0 && side * v.z() < 0.0) continue;
    const double y = h.at(v.x(), v.z());
    if (std::isfinite(y)) gap = std::min(gap, v.y() - y);
  }
  return std::isfinite(gap) ? gap : kNan;
}

Eigen::Matrix3d rotation_xyz_deg(const std::array<double, 3>& deg) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(deg[2] * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(deg[1] * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(deg[0] * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// the rotation_deg that turns the current one a further 180 deg about y (AP and ML reversed)
std::array<double, 3> turned_about_y(const std::array<double, 3>& deg) {
  if (deg[0] == 0.0 && deg[2] == 0.0) {
    double y = deg[1] + 180.0;
    if (y > 180.0) y -= 360.0;
    return {0.0, y, 0.0};
  }
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).toRotationMatrix() *
      rotation_xyz_deg(deg);
  // R = Rz(c) Ry(b) Rx(a): Eigen's eulerAngles(2, 1, 0) gives (c, b, a)
  const Eigen::Vector3d zyx = R.eulerAngles(2, 1, 0) * (180.0 / std::numbers::pi);
  std::array<double, 3> out{zyx[2], zyx[1], zyx[0]};
  for (double& v : out) {
    v = std::round(v * 10.0) / 10.0;
    if (v <= -180.0) v += 360.0;
    if (v > 180.0) v -= 360.0;
    if (v == 0.0) v = 0.0;
  }
  return out;
}

}  // namespace

void check_implant(const Config& c, const Implant& imp) {
  if (c.implant_kind != "mesh") return;
  const std::filesystem::path femur_file = resolve_path(c, c.femur_mesh);
  const std::filesystem::path insert_file = resolve_path(c, c.insert_mesh);
  const std::string femur_name = femur_file.filename().string();
  const std::string insert_name = insert_file.filename().string();

  // the same mesh twice
  if (same_file_bytes(femur_file, insert_file) || same_shape(imp.femur, imp.insert)) {
    throw InputError(config_name(c) + ": implant.mesh.femur and implant.mesh.insert are the "
                     "same mesh ('" + femur_file.string() + "' and '" + insert_file.string() +
                     "'); allowed: two different meshes, the femoral component and the tibial "
                     "insert.");
  }

  // inside-out components: the contact and the wear volume need outward normals
  const MeshCheck insert_check = check_mesh(imp.insert);
  if (insert_check.closed()) {
    const double v = enclosed_volume(imp.insert);
    if (v <= 0.0) {
      throw InputError(insert_file.string() + ": implant.mesh.insert is inside out: its "
                       "triangles wind clockwise seen from outside (enclosed volume " +
                       fmt("%.0f", v / (kMm * kMm * kMm)) + " mm^3); allowed: counter-clockwise "
                       "winding (outward normals, positive volume), i.e. reverse the vertex "
                       "order of every triangle.");
    }
  }
  if (check_mesh(imp.femur).closed() && enclosed_volume(imp.femur) <= 0.0) {
    throw InputError(femur_file.string() + ": implant.mesh.femur is inside out: its triangles "
                     "wind clockwise seen from outside (enclosed volume " +
                     fmt("%.0f", enclosed_volume(imp.femur) / (kMm * kMm * kMm)) +
                     " mm^3); allowed: counter-clockwise winding (outward normals, positive "
                     "volume), i.e. reverse the vertex order of every triangle.");
  }

  // an upside-down insert: its flat base at the top (a closed insert has a base)
  if (insert_check.closed()) {
    const FlatAreas flat = find_flat_areas(imp.insert);
    if (flat.top > flat.bottom) {
      throw InputError(insert_file.string() + ": implant.mesh.insert is upside down in the "
                       "project frame: its flat base (" + fmt("%.0f", flat.top / (kMm * kMm)) +
                       " mm^2 facing +y) is at the top and the articular surface faces down "
                       "(implant.mesh.rotation_deg = " + vec_mm(c.mesh_rotation_deg) +
                       "); allowed: +y from the base to the articular surface, e.g. a further "
                       "180 deg about x or z.");
    }
  }

  // an upside-down femur: its lowest parts are no condylar arcs
  for (int side : {-1, 1}) {
    const CondyleArc arc = fit_condyle_arc(imp.femur, side);
    if (arc.found && (arc.radius_mm < kMinArcRadius_mm || arc.radius_mm > kMaxArcRadius_mm)) {
      throw InputError(femur_file.string() + ": implant.mesh.femur's lowest part on the " +
                       (side < 0 ? "medial" : "lateral") + " side is no distal condylar arc "
                       "(sagittal radius " + fmt("%.1f", arc.radius_mm) + " mm; allowed: " +
                       fmt("%.0f", kMinArcRadius_mm) + " to " + fmt("%.0f", kMaxArcRadius_mm) +
                       " mm): is the femur upside down (implant.mesh.rotation_deg = " +
                       vec_mm(c.mesh_rotation_deg) + ", +y must point superior) or is "
                       "implant.mesh.femur another part?");
    }
  }

  // the femoral condyles over the insert: the run puts F's origin over T's origin
  const auto fbox = bounding_box(imp.femur);
  const auto ibox = bounding_box(imp.insert);
  Eigen::Vector3d low_sum = Eigen::Vector3d::Zero();
  int low_count = 0;
  for (const auto& v : imp.femur.vertices) {
    if (v.y() < fbox.min().y() + 3.0 * kMm) low_sum += v, ++low_count;
  }
  const Eigen::Vector3d low = low_sum / std::max(low_count, 1);
  if (low.x() < ibox.min().x() || low.x() > ibox.max().x() || low.z() < ibox.min().z() ||
      low.z() > ibox.max().z()) {
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "%s: the femoral component is not above the insert: its lowest points are "
                  "at x = %.1f, z = %.1f mm about the flexion axis (implant.mesh.femur_origin_mm"
                  " = %s), while the insert (%s) spans x %.1f to %.1f, z %.1f to %.1f mm; "
                  "allowed: both meshes in one frame with the condyles over the insert.",
                  femur_file.string().c_str(), low.x() / kMm, low.z() / kMm,
                  vec_mm(c.femur_origin_mm).c_str(), insert_name.c_str(), ibox.min().x() / kMm,
                  ibox.max().x() / kMm, ibox.min().z() / kMm, ibox.max().z() / kMm);
    throw InputError(buf);
  }

  // the flexion axis (F's origin) through the femoral component
  const Eigen::Vector3d m = Eigen::Vector3d::Constant(kAxisMargin_mm * kMm);
  const Eigen::Vector3d lo = fbox.min() - m, hi = fbox.max() + m;
  const bool inside = lo.x() <= 0 && hi.x() >= 0 && lo.z() <= 0 && hi.z() >= 0 &&
                      fbox.min().y() + kAxisAboveLowest_mm * kMm <= 0 && hi.y() >= 0;
  if (!inside) {
    const CondyleArc a = fit_condyle_arc(imp.femur, -1), b = fit_condyle_arc(imp.femur, 1);
    std::string fitted;
    if (a.found && b.found) {
      const Eigen::Vector3d centre(0.5 * (a.x_mm + b.x_mm) + c.femur_origin_mm[0],
                                   0.5 * (a.y_mm + b.y_mm) + c.femur_origin_mm[1],
                                   c.femur_origin_mm[2]);
      fitted = " (the distal condylar arcs' centre is at " + vec_mm(centre) + ")";
    }
    char buf[700];
    std::snprintf(buf, sizeof buf,
                  "%s: implant.mesh.femur_origin_mm = %s puts the flexion axis outside the "
                  "femoral component (%s spans x %.1f to %.1f, y %.1f to %.1f mm about it); "
                  "allowed: an axis through the component at least %.0f mm above its lowest "
                  "point, near the centre of its distal condylar arcs%s.",
                  config_name(c).c_str(), vec_mm(c.femur_origin_mm).c_str(),
                  femur_name.c_str(), fbox.min().x() / kMm, fbox.max().x() / kMm,
                  fbox.min().y() / kMm, fbox.max().y() / kMm, kAxisAboveLowest_mm,
                  fitted.c_str());
    throw InputError(buf);
  }
}

ImplantFacts describe_implant(const Config& c, const Implant& imp,
                              const engine::InsertSurface& surface) {
  ImplantFacts f;
  const Eigen::Vector3d origin(c.femur_origin_mm[0], c.femur_origin_mm[1], c.femur_origin_mm[2]);
  const Eigen::Vector3d base(0, c.implant_kind == "mesh" ? c.insert_base_y_mm : 0.0, 0);
  const Eigen::Vector3d femur_shift = c.implant_kind == "mesh" ? origin : Eigen::Vector3d::Zero();
  const auto fbox = bounding_box(imp.femur);
  const auto ibox = bounding_box(imp.insert);
  f.femur_min_mm = fbox.min() / kMm + femur_shift;
  f.femur_max_mm = fbox.max() / kMm + femur_shift;
  f.insert_min_mm = ibox.min() / kMm + base;
  f.insert_max_mm = ibox.max() / kMm + base;
  f.femur_triangles = static_cast<int>(imp.femur.triangles.size());
  f.insert_triangles = static_cast<int>(imp.insert.triangles.size());
  f.femur_closed = check_mesh(imp.femur).closed();
  f.insert_closed = check_mesh(imp.insert).closed();
  constexpr double kMm3 = kMm * kMm * kMm;
  if (f.femur_closed) f.femur_volume_mm3 = enclosed_volume(imp.femur) / kMm3;
  if (f.insert_closed) f.insert_volume_mm3 = enclosed_volume(imp.insert) / kMm3;

  // the articular faces the run will use
  f.articular_elements = surface.size();
  f.articular_min_mm = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  f.articular_max_mm = -f.articular_min_mm;
  for (int e = 0; e < surface.size(); ++e) {
    const double a = surface.area[e] / (kMm * kMm);
    f.articular_area_mm2 += a;
    (surface.medial[e] ? f.medial_area_mm2 : f.lateral_area_mm2) += a;
  }
  for (const auto& v : surface.vertices_T) {
    f.articular_min_mm = f.articular_min_mm.cwiseMin(v / kMm);
    f.articular_max_mm = f.articular_max_mm.cwiseMax(v / kMm);
  }

  const ImplantFacts frame = describe_frame(c, imp);
  f.arcs[0] = frame.arcs[0];
  f.arcs[1] = frame.arcs[1];
  f.suggested_origin_mm = frame.suggested_origin_mm;
  f.flange_x_mm = frame.flange_x_mm;
  f.warnings = frame.warnings;

  // gaps: as in the files, and as the run starts (femur 1 mm above the articular top)
  const std::vector<int> faces = articular_faces(imp.insert, c.articular_min_normal_y);
  const HeightMap height(imp.insert, faces, 0.25 * kMm);
  // files: femur at F + origin, insert at T + base; in T: femur at F + origin - base
  f.files_gap_mm = find_gap(imp.femur, (femur_shift - base) * kMm, height, 0) / kMm;
  const double start_y = f.articular_max_mm.y() * kMm - fbox.min().y() + kStartPlacement_mm * kMm;
  const Eigen::Vector3d start(0, start_y, 0);
  f.start_gap_medial_mm = find_gap(imp.femur, start, height, -1) / kMm;
  f.start_gap_lateral_mm = find_gap(imp.femur, start, height, 1) / kMm;

  if (c.implant_kind != "mesh") return f;
  char buf[600];
  const double base_off = f.insert_min_mm.y() - c.insert_base_y_mm;
  if (std::abs(base_off) > kBaseWarn_mm) {
    std::snprintf(buf, sizeof buf,
                  "base plane: the insert's lowest point is at y = %.2f mm but "
                  "implant.mesh.insert_base_y_mm = %g; the layer thickness (and the contact "
                  "stiffness) is measured from insert_base_y_mm: set it to %.2f unless the "
                  "insert sits on the tray elsewhere.",
                  f.insert_min_mm.y(), c.insert_base_y_mm, f.insert_min_mm.y());
    f.warnings.push_back(buf);
  }
  if (!f.insert_closed) {
    f.warnings.push_back("volume: the insert mesh is open (implant.mesh.insert_closed = false), "
                         "so wear volume is measured by depth only.");
  }
  return f;
}

void warn_about_frame(const Config& c, const Implant& imp) {
  if (c.implant_kind != "mesh") return;
  const ImplantFacts frame = describe_frame(c, imp);
  static std::mutex mutex;
  static std::set<std::string> said;
  std::lock_guard<std::mutex> lock(mutex);
  for (const std::string& w : frame.warnings) {
    if (!said.insert(w).second) continue;
    std::fprintf(stderr, "warning: %s: %s (kneesim implant check CONFIG shows the frame)\n",
                 config_name(c).c_str(), w.c_str());
  }
}

ImplantFacts describe_frame(const Config& c, const Implant& imp) {
  ImplantFacts f;
  const Eigen::Vector3d origin(c.femur_origin_mm[0], c.femur_origin_mm[1], c.femur_origin_mm[2]);
  const auto fbox = bounding_box(imp.femur);
  // the flexion axis against the distal condylar arcs
  f.arcs[0] = fit_condyle_arc(imp.femur, -1);
  f.arcs[1] = fit_condyle_arc(imp.femur, 1);
  f.suggested_origin_mm = origin;
  if (f.arcs[0].found && f.arcs[1].found) {
    f.suggested_origin_mm.x() = std::round((0.5 * (f.arcs[0].x_mm + f.arcs[1].x_mm) + origin.x()) * 10) / 10;
    f.suggested_origin_mm.y() = std::round((0.5 * (f.arcs[0].y_mm + f.arcs[1].y_mm) + origin.y()) * 10) / 10;
  }

  // the anterior flange: the femoral component's highest point
  const Eigen::Vector3d* top = &imp.femur.vertices.front();
  for (const auto& v : imp.femur.vertices) {
    if (v.y() > top->y()) top = &v;
  }
  f.flange_x_mm = (top->x() - fbox.center().x()) / kMm;
  // with AP reversed, the suggested axis is given in the frame turned 180 deg about y, the
  // one the frame warning asks for: (x, y, z) -> (-x, y, -z)
  if (f.flange_x_mm < 0.0 && c.implant_kind == "mesh") {
    f.suggested_origin_mm.x() = -f.suggested_origin_mm.x() + 0.0;
    f.suggested_origin_mm.z() = -f.suggested_origin_mm.z() + 0.0;
  }

  if (c.implant_kind != "mesh") return f;
  char buf[600];
  if (f.flange_x_mm < 0.0) {
    std::snprintf(buf, sizeof buf,
                  "frame: the femoral component's highest point (its anterior flange) lies "
                  "%.1f mm posterior of its centre, but the project frame has +x anterior: "
                  "with implant.mesh.rotation_deg = %s anterior and posterior (and medial and "
                  "lateral) are reversed; set rotation_deg = %s (turns the meshes a further "
                  "180 deg about y).",
                  -f.flange_x_mm, vec_mm(c.mesh_rotation_deg).c_str(),
                  vec_mm(turned_about_y(c.mesh_rotation_deg)).c_str());
    f.warnings.push_back(buf);
  }
  if (f.arcs[0].found && f.arcs[1].found) {
    const double off = std::hypot(0.5 * (f.arcs[0].x_mm + f.arcs[1].x_mm),
                                  0.5 * (f.arcs[0].y_mm + f.arcs[1].y_mm));
    if (off > kAxisWarn_mm || f.flange_x_mm < 0.0) {
      std::snprintf(buf, sizeof buf,
                    "flexion axis: implant.mesh.femur_origin_mm = %s is %.1f mm from the "
                    "centre of the distal condylar arcs (radii %.1f and %.1f mm); the run "
                    "flexes the femur about femur_origin_mm: set it to %s%s unless your rig's "
                    "axis is elsewhere.",
                    vec_mm(c.femur_origin_mm).c_str(), off, f.arcs[0].radius_mm,
                    f.arcs[1].radius_mm, vec_mm(f.suggested_origin_mm).c_str(),
                    f.flange_x_mm < 0.0 ? " (the arcs' centre in the turned frame, with the "
                                          "rotation_deg above)" : "");
      f.warnings.push_back(buf);
    }
  }
  return f;
}

}  // namespace kneesim::models
