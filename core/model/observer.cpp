#include "core/model/observer.hpp"

namespace stoss::model {

int SeriesLayout::index_of(const std::string& name) const {
  int offset = 0;
  for (const auto& s : series) {
    if (s.name == name) return offset;
    offset += s.components;
  }
  return -1;
}

int SeriesLayout::row_size() const {
  int n = 0;
  for (const auto& s : series) n += s.components;
  return n;
}

}  // namespace stoss::model
