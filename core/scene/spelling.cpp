#include "core/scene/spelling.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace stoss::scene::detail {

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), size_t{0});
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substituted = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substituted});
    }
  }
  return row[b.size()];
}

std::optional<std::string> closest_name(std::string_view name,
                                        std::initializer_list<std::string_view> allowed) {
  std::optional<std::string> best;
  size_t best_distance = 3;  // at most 2 edits
  for (std::string_view candidate : allowed) {
    const size_t d = edit_distance(name, candidate);
    if (d < best_distance && 3 * d < std::max(name.size(), candidate.size())) {
      best = std::string(candidate);
      best_distance = d;
    }
  }
  return best;
}

std::string unknown_field_message(std::string_view key, std::initializer_list<std::string_view> allowed) {
  const auto guess = closest_name(key, allowed);
  return guess ? "unknown field; did you mean \"" + *guess + "\"?" : "unknown field";
}

}  // namespace stoss::scene::detail
