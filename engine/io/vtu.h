// VTK XML UnstructuredGrid (.vtu) writer for ParaView: a hexahedral mesh (the deformable
// insert) with named point and cell arrays (ASCII, like the .vtp writer). Positions in mm.
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <vector>

#include "engine/io/vtp.h"

namespace kneesim::io {

struct VtuHexMesh {
  std::vector<Eigen::Vector3d> points_mm;  // node positions [mm]
  std::vector<std::array<int, 8>> hexes;   // node ids in VTK_HEXAHEDRON order
  std::vector<VtpArray> point_data;
  std::vector<VtpArray> cell_data;
};

void write_vtu(const std::filesystem::path& path, const VtuHexMesh& mesh);

}  // namespace kneesim::io
