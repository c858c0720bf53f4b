#include "models/hex_mesh.h"

namespace kneesim::models {

HexMesh make_box_hex_mesh(int nx, int ny, int nz, const Eigen::Vector3d& size,
                          const Eigen::Vector3d& origin) {
  HexMesh m;
  m.nx = nx;
  m.ny = ny;
  m.nz = nz;
  m.nodes.reserve(static_cast<size_t>(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        m.nodes.push_back(origin + Eigen::Vector3d(size.x() * i / nx, size.y() * j / ny,
                                                   size.z() * k / nz));
  m.elements.reserve(static_cast<size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.elements.push_back({m.node(i, j, k), m.node(i + 1, j, k), m.node(i + 1, j + 1, k),
                              m.node(i, j + 1, k), m.node(i, j, k + 1), m.node(i + 1, j, k + 1),
                              m.node(i + 1, j + 1, k + 1), m.node(i, j + 1, k + 1)});
  return m;
}

}  // namespace kneesim::models
