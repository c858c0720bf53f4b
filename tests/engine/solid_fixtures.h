// Structured box meshes and helpers for the hex8 solid tests.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/solid/solid_build.h"
#include "engine/solid/solid_step.h"
#include "models/hex_mesh.h"

namespace kneesim::test {

using BoxMesh = models::HexMesh;

inline BoxMesh make_box(int nx, int ny, int nz, const Eigen::Vector3d& size,
                        const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
  return models::make_box_hex_mesh(nx, ny, nz, size, origin);
}

// moves every interior node of the mesh by up to `fraction` of the element size (seeded): a
// distorted mesh with the box's boundary and volume unchanged
inline void distort_interior(BoxMesh& m, double fraction, const Eigen::Vector3d& size,
                             unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 1; k < m.nz; ++k)
    for (int j = 1; j < m.ny; ++j)
      for (int i = 1; i < m.nx; ++i) {
        Eigen::Vector3d d(size.x() / m.nx * u(rng), size.y() / m.ny * u(rng),
                          size.z() / m.nz * u(rng));
        m.nodes[m.node(i, j, k)] += fraction * d;
      }
}

inline engine::solid::SolidMaterial make_elastic(double E, double nu, double rho) {
  engine::solid::SolidMaterial mat;
  mat.kind = engine::solid::SolidMaterialKind::kElastic;
  mat.youngs_modulus = E;
  mat.poisson = nu;
  mat.density = rho;
  return mat;
}

// UHMWPE of physics.md: E 685 MPa, nu 0.47, rho 935 kg/m^3, yield 17 MPa rising with
// H = (33 - 17) / 0.32 MPa to a cap of 33 MPa
inline engine::solid::SolidMaterial make_uhmwpe_plastic() {
  engine::solid::SolidMaterial mat = make_elastic(685e6, 0.47, 935.0);
  mat.kind = engine::solid::SolidMaterialKind::kJ2Plastic;
  mat.yield_stress = 17e6;
  mat.hardening_modulus = (33e6 - 17e6) / 0.32;
  mat.yield_cap = 33e6;
  return mat;
}

}  // namespace kneesim::test
