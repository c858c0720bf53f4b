#include "engine/io/vtp.h"

#include <cstdio>
#include <stdexcept>

#include "engine/io/atomic_file.h"

namespace kneesim::io {

void append_vtk_array(std::string& out, const VtpArray& a, size_t expected, const char* where) {
  if (a.values.size() != expected) {
    throw std::logic_error(std::string("vtk ") + where + " array " + a.name + " has " +
                           std::to_string(a.values.size()) + " values, expected " +
                           std::to_string(expected));
  }
  out += "<DataArray type=\"Float64\" Name=\"" + a.name + "\" format=\"ascii\">\n";
  char buf[40];
  for (double v : a.values) {
    std::snprintf(buf, sizeof buf, "%.9g ", v);
    out += buf;
  }
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
  char buf[96];
  for (const auto& p : s.points_mm) {
    std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    out += buf;
  }
  out += "</DataArray>\n</Points>\n<Polys>\n";
  out += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : s.triangles) {
    std::snprintf(buf, sizeof buf, "%d %d %d\n", t.x(), t.y(), t.z());
    out += buf;
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
