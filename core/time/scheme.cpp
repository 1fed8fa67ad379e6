#include "core/time/scheme.hpp"

#include "core/time/energy_momentum.hpp"
#include "core/time/generalized_alpha.hpp"
#include "core/time/midpoint.hpp"
#include "core/time/static_scheme.hpp"

namespace stoss::time {

std::unique_ptr<Scheme> make_scheme(const model::TimeSpec& time) {
  switch (time.scheme) {
    case model::Scheme::midpoint:
      return std::make_unique<Midpoint>();
    case model::Scheme::energy_momentum:
      return std::make_unique<EnergyMomentum>();
    case model::Scheme::hht:
      return std::make_unique<GeneralizedAlpha>(GeneralizedAlpha::hht(time.alpha));
    case model::Scheme::generalized_alpha:
      return std::make_unique<GeneralizedAlpha>(GeneralizedAlpha::chung_hulbert(time.rho_infinity));
    case model::Scheme::equilibrium:
      return std::make_unique<Static>();
  }
  return nullptr;
}

}  // namespace stoss::time
