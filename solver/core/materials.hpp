#pragma once
// Materials, interactions between pairs of materials, and the per-pair constants the contact
// kernels need, computed once.
#include <cstdint>
#include <string>
#include <vector>

namespace seedcal {

struct Material {
  std::string name;
  double density_kg_m3 = 0.0;
  double youngs_modulus_pa = 0.0;
  double poisson_ratio = 0.0;

  // G = E / (2 (1 + nu)), isotropic linear elasticity.
  double shear_modulus_pa() const { return youngs_modulus_pa / (2.0 * (1.0 + poisson_ratio)); }
};

// What the user sets for one pair of materials that can touch.
struct Interaction {
  std::string name;
  std::uint16_t material_a = 0;
  std::uint16_t material_b = 0;
  double restitution = 0.5;
  double static_friction = 0.5;
  double rolling_friction = 0.0;
};

// Constants of one material pair, precomputed for the kernels (Hertz-Mindlin, DESIGN.md):
//   1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j
//   1/G* = (2 - nu_i)/G_i + (2 - nu_j)/G_j
//   beta = ln e / sqrt(ln^2 e + pi^2)       (beta <= 0; beta = 0 for e = 1)
struct PairConstants {
  double e_star_pa = 0.0;
  double g_star_pa = 0.0;
  double beta = 0.0;
  double static_friction = 0.0;
  double rolling_friction = 0.0;
  double restitution = 1.0;
  double sqrt_tangential_ratio = 0.0;  // sqrt(S_t / S_n) = sqrt(4 G* / E*), constant per pair
  bool defined = false;  // false: the pair has no interaction and must not touch
};

double damping_beta(double restitution);

class InteractionTable {
 public:
  InteractionTable() = default;
  InteractionTable(std::vector<Material> materials, const std::vector<Interaction>& interactions);

  const PairConstants& pair(std::uint16_t a, std::uint16_t b) const {
    return table_[static_cast<std::size_t>(a) * n_ + b];
  }
  const std::vector<Material>& materials() const { return materials_; }
  std::size_t material_count() const { return n_; }
  bool any_rolling_friction() const;

 private:
  std::vector<Material> materials_;
  std::size_t n_ = 0;
  std::vector<PairConstants> table_;
};

}  // namespace seedcal
