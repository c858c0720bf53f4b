// VTK XML PolyData (.vtp) writer for ParaView: a triangle surface with named point and cell
// arrays (ASCII, so files diff and open anywhere). Positions are written in millimetres.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace kneesim::io {

struct VtpArray {
  std::string name;            // with unit suffix, e.g. "pressure_MPa"
  std::vector<double> values;  // one per point or per cell
};

struct VtpSurface {
  std::vector<Eigen::Vector3d> points_mm;      // vertex positions [mm]
  std::vector<Eigen::Vector3i> triangles;      // vertex indices
  std::vector<VtpArray> point_data;
  std::vector<VtpArray> cell_data;
};

// appends one ASCII DataArray; throws std::logic_error when it does not hold `expected` values
void append_vtk_array(std::string& out, const VtpArray& array, size_t expected,
                      const char* where);

// the file's text (the size of a run's outputs is estimated from it before the run)
std::string format_vtp(const VtpSurface& surface);

// writes format_vtp(surface) atomically
void write_vtp(const std::filesystem::path& path, const VtpSurface& surface);

}  // namespace kneesim::io
