#include "core/fem/material.hpp"

#include <stdexcept>

#include "core/fem/neo_hookean.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"

namespace stoss::fem {

Vector6d to_voigt_stress(const Eigen::Matrix3d& S) {
  Vector6d s;
  s << S(0, 0), S(1, 1), S(2, 2), S(1, 2), S(0, 2), S(0, 1);
  return s;
}

Lame Lame::from(double E, double nu) {
  return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};  // (1.5)
}

const std::vector<std::string_view>& material_models() {
  static const std::vector<std::string_view> names = {"saint_venant_kirchhoff", "neo_hookean"};
  return names;
}

std::shared_ptr<const Material> make_material(const model::Material& spec) {
  if (spec.model == "saint_venant_kirchhoff")
    return std::make_shared<SaintVenantKirchhoff>(spec.youngs_modulus, spec.poisson_ratio);
  if (spec.model == "neo_hookean")
    return std::make_shared<NeoHookean>(spec.youngs_modulus, spec.poisson_ratio);
  throw std::invalid_argument("material model \"" + spec.model + "\" is unknown");
}

}  // namespace stoss::fem
