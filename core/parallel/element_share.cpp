#include "core/parallel/element_share.hpp"

#include <algorithm>

namespace stoss::parallel {
namespace {
ElementShare& current() {
  static ElementShare share;
  return share;
}
}  // namespace

ElementShare share_of(const Elements& hex8, std::vector<int> node_part, int rank, int size,
                      std::function<void(double*, long)> sum) {
  ElementShare share{rank, size, std::move(sum), std::move(node_part), {}};
  for (int e = 0; e < static_cast<int>(hex8.size()); ++e)
    if (std::any_of(hex8[e].begin(), hex8[e].end(), [&](int node) { return share.owns(node); }))
      share.elements.push_back(e);
  return share;
}

void node_graph(const Elements& hex8, int nodes, std::vector<int>& offsets, std::vector<int>& neighbours) {
  std::vector<std::vector<int>> adjacent(nodes);
  for (const std::array<int, 8>& hex : hex8)
    for (int a : hex)
      for (int b : hex)
        if (a != b) adjacent[a].push_back(b);
  offsets.assign(1, 0);
  neighbours.clear();
  for (std::vector<int>& list : adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    neighbours.insert(neighbours.end(), list.begin(), list.end());
    offsets.push_back(static_cast<int>(neighbours.size()));
    std::vector<int>().swap(list);
  }
}

std::vector<char> ElementShare::own_rows() const {
  std::vector<char> rows(3 * node_part.size());
  for (size_t node = 0; node < node_part.size(); ++node)
    rows[3 * node] = rows[3 * node + 1] = rows[3 * node + 2] = owns(static_cast<int>(node));
  return rows;
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
