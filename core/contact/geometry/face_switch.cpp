#include "core/contact/geometry/face_switch.hpp"

#include <algorithm>

namespace stoss::contact {

double switched_gap_target(model::SwitchGap rule, model::ImpactMode impact, double new_gap, double target) {
  if (rule == model::SwitchGap::keep) return new_gap;  // §3.4: keep is energy-exact
  const bool frozen = impact == model::ImpactMode::persist || impact == model::ImpactMode::located;
  return frozen ? std::min(std::max(new_gap, 0.0), target) : 0.0;
}

double switched_gap_offset(model::SwitchGap rule, double kept, double new_gap) {
  if (rule != model::SwitchGap::keep) return 0;  // clamp: the new face's true gap from now on
  return kept < 0 ? new_gap - kept : std::min(new_gap, 0.0);
}

}  // namespace stoss::contact
