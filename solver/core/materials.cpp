#include "solver/core/materials.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace seedcal {

double damping_beta(double restitution) {
  // Tsuji et al. (1992) / EDEM theory reference: beta = ln e / sqrt(ln^2 e + pi^2).
  if (restitution >= 1.0) return 0.0;
  if (restitution <= 0.0) return -1.0;  // limit e -> 0
  const double l = std::log(restitution);
  return l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

InteractionTable::InteractionTable(std::vector<Material> materials,
                                   const std::vector<Interaction>& interactions)
    : materials_(std::move(materials)), n_(materials_.size()), table_(n_ * n_) {
  for (const Interaction& it : interactions) {
    if (it.material_a >= n_ || it.material_b >= n_)
      throw std::invalid_argument("interaction '" + it.name + "' names an unknown material index");
    const Material& a = materials_[it.material_a];
    const Material& b = materials_[it.material_b];
    PairConstants c;
    c.e_star_pa = 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus_pa +
                         (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus_pa);
    c.g_star_pa = 1.0 / ((2.0 - a.poisson_ratio) / a.shear_modulus_pa() +
                         (2.0 - b.poisson_ratio) / b.shear_modulus_pa());
    c.beta = damping_beta(it.restitution);
    // S_t / S_n = 8 G* sqrt(R* d) / (2 E* sqrt(R* d)) = 4 G* / E*.
    c.sqrt_tangential_ratio = std::sqrt(4.0 * c.g_star_pa / c.e_star_pa);
    c.static_friction = it.static_friction;
    c.rolling_friction = it.rolling_friction;
    c.restitution = it.restitution;
    c.defined = true;
    table_[static_cast<std::size_t>(it.material_a) * n_ + it.material_b] = c;
    table_[static_cast<std::size_t>(it.material_b) * n_ + it.material_a] = c;
  }
}

bool InteractionTable::any_rolling_friction() const {
  for (const auto& c : table_)
    if (c.defined && c.rolling_friction > 0.0) return true;
  return false;
}

}  // namespace seedcal
