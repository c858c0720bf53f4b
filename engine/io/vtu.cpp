#include "engine/io/vtu.h"

#include <cstdio>
#include <string>

#include "engine/io/atomic_file.h"

namespace kneesim::io {
void write_vtu(const std::filesystem::path& path, const VtuHexMesh& m) {
  constexpr int kVtkHexahedron = 12;
  std::string out;
  out.reserve(80 * (m.points_mm.size() + m.hexes.size()));
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid>\n";
  out += "<Piece NumberOfPoints=\"" + std::to_string(m.points_mm.size()) +
         "\" NumberOfCells=\"" + std::to_string(m.hexes.size()) + "\">\n";
  out += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  char buf[128];
  for (const auto& p : m.points_mm) {
    std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    out += buf;
  }
  out += "</DataArray>\n</Points>\n<Cells>\n";
  out += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& h : m.hexes) {
    std::snprintf(buf, sizeof buf, "%d %d %d %d %d %d %d %d\n", h[0], h[1], h[2], h[3], h[4],
                  h[5], h[6], h[7]);
    out += buf;
  }
  out += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t i = 0; i < m.hexes.size(); ++i) out += std::to_string(8 * (i + 1)) + '\n';
  out += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t i = 0; i < m.hexes.size(); ++i) out += std::to_string(kVtkHexahedron) + '\n';
  out += "</DataArray>\n</Cells>\n";
  if (!m.point_data.empty()) {
    out += "<PointData>\n";
    for (const auto& a : m.point_data) append_vtk_array(out, a, m.points_mm.size(), "point");
    out += "</PointData>\n";
  }
  if (!m.cell_data.empty()) {
    out += "<CellData>\n";
    for (const auto& a : m.cell_data) append_vtk_array(out, a, m.hexes.size(), "cell");
    out += "</CellData>\n";
  }
  out += "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  write_file_atomic(path, out);
}

}  // namespace kneesim::io
