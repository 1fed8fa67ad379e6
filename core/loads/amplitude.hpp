#pragma once
/// @file The time factor of a load or a prescribed motion: piecewise linear in time (docs/theory.md §5b.1).

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace stoss::loads {

/// a(t) from points [[t0, f0], [t1, f1], …]: linear between points, constant beyond the first and the last,
/// 1 without points (docs/theory.md (5b.1)).
class Amplitude {
 public:
  using Point = std::array<double, 2>;  ///< [time, factor]

  Amplitude() = default;
  /// @throws std::invalid_argument with the rule broken (amplitude_rule_broken) when the points are not
  /// valid.
  explicit Amplitude(std::vector<Point> points);

  double operator()(double t) const;
  const std::vector<Point>& points() const { return points_; }

 private:
  std::vector<Point> points_;
};

/// A rule an amplitude breaks: where (a JSON pointer relative to the amplitude, e.g. "/2/0") and the rule.
struct AmplitudeViolation {
  std::string where;
  std::string rule;
};

/// Which kind of entry an amplitude scales: a displacement needs a(0) = 0 (so that the body starts where
/// its mesh is); a load does not.
enum class AmplitudeUse { load, displacement };

/// The first rule the points break, or nullopt: every time and factor finite, times strictly increasing,
/// and for a displacement a(0) = 0. The scene validator prefixes `where` with the amplitude's pointer.
std::optional<AmplitudeViolation> amplitude_rule_broken(const std::vector<Amplitude::Point>& points,
                                                        AmplitudeUse use = AmplitudeUse::load);

}  // namespace stoss::loads
