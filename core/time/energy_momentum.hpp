#pragma once
/// @file Energy–momentum scheme (docs/theory.md §2.3): midpoint kinematics, discrete-gradient forces.

#include "core/time/midpoint.hpp"

namespace stoss::time {

/// Conserves energy (to the Newton tolerance) and both momenta of a free system.
class EnergyMomentum : public MidpointKinematics {
 public:
  ForceRule force_rule() const override { return ForceRule::discrete_gradient(); }
};

}  // namespace stoss::time
