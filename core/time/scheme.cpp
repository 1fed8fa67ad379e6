#include "core/time/scheme.hpp"

#include "core/time/energy_momentum.hpp"
#include "core/time/hht.hpp"
#include "core/time/midpoint.hpp"

namespace stoss::time {

std::unique_ptr<Scheme> make_scheme(model::Scheme scheme, double alpha) {
  switch (scheme) {
    case model::Scheme::midpoint: return std::make_unique<Midpoint>();
    case model::Scheme::energy_momentum: return std::make_unique<EnergyMomentum>();
    case model::Scheme::hht: return std::make_unique<Hht>(alpha);
  }
  return nullptr;
}

}  // namespace stoss::time
