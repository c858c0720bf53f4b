#include "engine/io/vtp.h"

#include <charconv>
#include <cstdio>
#include <stdexcept>

#include "engine/io/atomic_file.h"

namespace kneesim::io {
namespace {

// v as printf's "%.9g" writes it (std::to_chars with a precision is specified as printf's
// conversion, C locale), about five times cheaper than snprintf: a wear run's 21 depth maps
// and a run's pressure maps spent more time formatting than a gait cycle (CHANGELOG.md, performance round 3)
void append_g9(std::string& out, double v, char after) {
  char buf[40];
  char* end = std::to_chars(buf, buf + sizeof buf - 1, v, std::chars_format::general, 9).ptr;
  *end++ = after;
  out.append(buf, end);
}

void append_int(std::string& out, int v, char after) {
  char buf[16];
  char* end = std::to_chars(buf, buf + sizeof buf - 1, v).ptr;
  *end++ = after;
  out.append(buf, end);
}

}  // namespace

void append_vtk_array(std::string& out, const VtpArray& a, size_t expected, const char* where) {
  if (a.values.size() != expected) {
    throw std::logic_error(std::string("vtk ") + where + " array " + a.name + " has " +
                           std::to_string(a.values.size()) + " values, expected " +
                           std::to_string(expected));
  }
  out += "<DataArray type=\"Float64\" Name=\"" + a.name + "\" format=\"ascii\">\n";
  for (double v : a.values) append_g9(out, v, ' ');
  out += "\n</DataArray>\n";
}

std::string format_vtp(const VtpSurface& s) {
  std::string out;
  out.reserve(64 * (s.points_mm.size() + s.triangles.size()));
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n";
  out += "<Piece NumberOfPoints=\"" + std::to_string(s.points_mm.size()) +
         "\" NumberOfPolys=\"" + std::to_string(s.triangles.size()) + "\">\n";
  out += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& p : s.points_mm) {
    append_g9(out, p.x(), ' ');
    append_g9(out, p.y(), ' ');
    append_g9(out, p.z(), '\n');
  }
  out += "</DataArray>\n</Points>\n<Polys>\n";
  out += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : s.triangles) {
    append_int(out, t.x(), ' ');
    append_int(out, t.y(), ' ');
    append_int(out, t.z(), '\n');
  }
  out += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t i = 0; i < s.triangles.size(); ++i) {
    out += std::to_string(3 * (i + 1));
    out += '\n';
  }
  out += "</DataArray>\n</Polys>\n";
  if (!s.point_data.empty()) {
    out += "<PointData>\n";
    for (const auto& a : s.point_data) append_vtk_array(out, a, s.points_mm.size(), "point");
    out += "</PointData>\n";
  }
  if (!s.cell_data.empty()) {
    out += "<CellData>\n";
    for (const auto& a : s.cell_data) append_vtk_array(out, a, s.triangles.size(), "cell");
    out += "</CellData>\n";
  }
  out += "</Piece>\n</PolyData>\n</VTKFile>\n";
  return out;
}

void write_vtp(const std::filesystem::path& path, const VtpSurface& s) {
  write_file_atomic(path, format_vtp(s));
}

}  // namespace kneesim::io
