#pragma once
// The seed's example (hollow ball onto a free plate) shortened for tests that run it many times: a
// coarse ball starting just above the plate, impact within the first steps, h = 0.01.
#include <nlohmann/json.hpp>
#include <string>

namespace stoss::test {

struct ShortBallOnPlate {
  /// "lagrange" (frictionless) or "penalty" (with Coulomb friction μ = 0.2).
  std::string enforcement = "lagrange";
  std::string scheme = "energy_momentum";
  bool persist = false;  ///< Lagrange impact "persist" instead of the default
  double end = 0.24;
  int checkpoint_every = 2;
};

inline nlohmann::json short_ball_on_plate(const ShortBallOnPlate& o) {
  nlohmann::json contact = {{"slave", "ball/outer"},
                            {"master", "plate/top"},
                            {"enforcement", o.enforcement},
                            {"switch_hysteresis", 0.05}};
  const bool friction = o.enforcement == "penalty";
  if (friction) contact["friction"] = 0.2;
  if (o.persist) contact["impact"] = "persist";
  const nlohmann::json material = {
      {"model", "saint_venant_kirchhoff"}, {"youngs_modulus", 1e4}, {"poisson_ratio", 0.4}, {"density", 1}};
  return {{"format", "stoss-scene/1"},
          {"name", friction ? "ball on plate with friction, shortened" : "ball on plate, shortened"},
          {"bodies",
           {{{"name", "ball"},
             {"mesh",
              {{"hollow_sphere",
                {{"center", {0, 0, 1.03}},
                 {"outer_radius", 1.0},
                 {"inner_radius", 0.8},
                 {"divisions", 4},
                 {"layers", 1}}}}},
             {"material", material},
             {"initial_velocity", {0, 1, -1}}},
            {{"name", "plate"},
             {"mesh", {{"box", {{"min", {-2, -1.5, -0.2}}, {"max", {2, 2.5, 0}}, {"divisions", {8, 8, 1}}}}}},
             {"material", material}}}},
          {"contact", {contact}},
          {"time", {{"scheme", o.scheme}, {"step", 0.01}, {"end", o.end}}},
          {"solver", {{"tolerance", 1e-10}, {"max_iterations", 25}}},
          {"output", {{"every", 3}, {"checkpoint_every", o.checkpoint_every}}}};
}

}  // namespace stoss::test
