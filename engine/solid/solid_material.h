// Solid materials of the deformable insert: linear elastic (St Venant-Kirchhoff in the total
// Lagrangian element, i.e. Hooke's law on the Green-Lagrange strain) and J2 elastoplastic
// with radial return and isotropic hardening (physics.md sections 5 and 6).
//
// Plasticity is additive on the Green-Lagrange strain, E = E_e + E_p, S = C : (E - E_p):
// the usual small-strain J2 model carried into a total Lagrangian element, valid for the
// small strains and moderate rotations of an insert (it is frame-indifferent, and reduces to
// the textbook model when the strains are small). Rejected: multiplicative finite-strain
// plasticity, which needs a polar or spectral decomposition per element and step and buys
// nothing at strains of a few per cent.
//
// Hardening: the yield stress rises linearly from sigma_y0 with slope H over the equivalent
// plastic strain and stays at sigma_cap beyond (UHMWPE: 17 MPa rising to 33 MPa at 0.32
// plastic strain, materials study: H = (33 - 17) / 0.32 = 50 MPa). Materials given a yield
// stress but no hardening are perfectly plastic.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace kneesim::engine::solid {

enum class SolidMaterialKind { kElastic, kJ2Plastic };

struct SolidMaterial {
  SolidMaterialKind kind = SolidMaterialKind::kElastic;
  double youngs_modulus = 0.0;   // E [Pa]
  double poisson = 0.0;          // nu [-], 0 <= nu < 0.5
  double density = 0.0;          // rho [kg/m^3]
  double yield_stress = 0.0;     // initial yield sigma_y0 [Pa] (J2 only)
  double hardening_modulus = 0.0;  // H, slope of yield stress over plastic strain [Pa]
  double yield_cap = 0.0;        // yield stress never exceeds this [Pa] (<= sigma_y0: none)

  double lame_lambda() const {
    return youngs_modulus * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  }
  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson)); }
  // P-wave (dilatational) modulus lambda + 2 mu [Pa]
  double dilatational_modulus() const { return lame_lambda() + 2.0 * shear_modulus(); }
};

// symmetric tensors in Voigt order xx, yy, zz, xy, yz, zx with tensor (not engineering) shear
using Sym6 = Eigen::Matrix<double, 6, 1>;

inline Sym6 to_voigt(const Eigen::Matrix3d& m) {
  Sym6 v;
  v << m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(1, 2), m(2, 0);
  return v;
}
inline Eigen::Matrix3d from_voigt(const Sym6& v) {
  Eigen::Matrix3d m;
  m << v[0], v[3], v[5], v[3], v[1], v[4], v[5], v[4], v[2];
  return m;
}

// the yield stress at equivalent plastic strain `alpha` [Pa]
inline double calc_yield_stress(const SolidMaterial& m, double alpha) {
  const double y = m.yield_stress + m.hardening_modulus * alpha;
  return m.yield_cap > m.yield_stress ? std::min(y, m.yield_cap) : y;
}

// result of one stress update at a material point
struct StressUpdate {
  Sym6 stress;             // S [Pa]
  Sym6 plastic_strain;     // E_p after the update [-]
  double alpha = 0.0;      // equivalent plastic strain after the update [-]
  double plastic_work = 0.0;  // dissipation of this update per unit volume [J/m^3]
};

// stress for Green-Lagrange strain `strain`, from the plastic state (plastic_strain, alpha)
// of the last converged step: elastic, or J2 radial return with the hardening above
StressUpdate calc_stress(const SolidMaterial& m, const Sym6& strain, const Sym6& plastic_strain,
                         double alpha);

// von Mises equivalent of a stress [Pa]
double calc_von_mises(const Sym6& s);

}  // namespace kneesim::engine::solid
