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

}  // namespace stoss::parallel
