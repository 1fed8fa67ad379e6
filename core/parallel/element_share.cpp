#include "core/parallel/element_share.hpp"

#include <algorithm>

namespace stoss::parallel {
namespace {
ElementShare& current() {
  static ElementShare share;
  return share;
}
}  // namespace

std::pair<int, int> ElementShare::range(int n) const {
  const auto start = [&](int k) { return k * (n / size) + std::min(k, n % size); };
  return {start(rank), start(rank + 1)};
}

const ElementShare& element_share() {
  return current();
}

void set_element_share(ElementShare share) {
  current() = std::move(share);
}

double total_over_ranks(double value) {
  if (current().shared()) current().sum(&value, 1);
  return value;
}

bool on_any_rank(bool asked) {
  return total_over_ranks(asked ? 1.0 : 0.0) > 0;
}

}  // namespace stoss::parallel
