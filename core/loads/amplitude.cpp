#include "core/loads/amplitude.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace stoss::loads {
namespace {

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

std::string pointer(size_t i, int component) {
  char text[48];
  std::snprintf(text, sizeof text, "/%zu/%d", i, component);
  return text;
}

}  // namespace

Amplitude::Amplitude(std::vector<Point> points) : points_(std::move(points)) {
  if (const auto broken = amplitude_rule_broken(points_))
    throw std::invalid_argument("amplitude" + broken->where + ": " + broken->rule);
}

double Amplitude::operator()(double t) const {
  if (points_.empty()) return 1;
  if (t <= points_.front()[0]) return points_.front()[1];
  if (t >= points_.back()[0]) return points_.back()[1];
  // The first point later than t; t lies in [previous, next) (5b.1).
  const auto next = std::upper_bound(points_.begin(), points_.end(), t,
                                     [](double time, const Point& p) { return time < p[0]; });
  const Point& a = *(next - 1);
  const Point& b = *next;
  const double s = (t - a[0]) / (b[0] - a[0]);
  return a[1] + s * (b[1] - a[1]);
}

std::optional<AmplitudeViolation> amplitude_rule_broken(const std::vector<Amplitude::Point>& points,
                                                        AmplitudeUse use) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i][0]))
      return AmplitudeViolation{pointer(i, 0), "an amplitude's times must be finite"};
    if (!std::isfinite(points[i][1]))
      return AmplitudeViolation{pointer(i, 1), "an amplitude's factors must be finite"};
    if (i > 0 && !(points[i][0] > points[i - 1][0]))
      return AmplitudeViolation{
          pointer(i, 0), "an amplitude's times must be increasing: " + number(points[i][0]) + " follows " +
                             number(points[i - 1][0])};
  }
  if (use == AmplitudeUse::displacement && !points.empty()) {
    const double at_zero = Amplitude(points)(0.0);
    if (at_zero != 0)
      return AmplitudeViolation{
          "",
          "a displacement's amplitude must be 0 at t = 0 (the body starts where its mesh "
          "is), but a(0) = " +
              number(at_zero)};
  }
  return std::nullopt;
}

}  // namespace stoss::loads
