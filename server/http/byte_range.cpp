#include "server/http/byte_range.hpp"

#include <limits>
#include <optional>

namespace stoss::server::http {

namespace {

/// Digits of text[begin, end) as a number, saturated at the largest uint64; nullopt when empty or not all
/// digits.
std::optional<std::uint64_t> number(const std::string& text, std::size_t begin, std::size_t end) {
  if (begin >= end) return std::nullopt;
  std::uint64_t value = 0;
  constexpr std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t i = begin; i < end; ++i) {
    const char c = text[i];
    if (c < '0' || c > '9') return std::nullopt;
    const auto digit = static_cast<std::uint64_t>(c - '0');
    value = value > (max - digit) / 10 ? max : value * 10 + digit;
  }
  return value;
}

std::string trimmed(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

}  // namespace

ByteRange resolve_range(const std::string& header, std::uint64_t size) {
  const ByteRange whole;
  const std::string value = trimmed(header);
  if (value.size() < 6 || value.compare(0, 6, "bytes=") != 0) return whole;
  const std::string spec = trimmed(value.substr(6));
  if (spec.find(',') != std::string::npos) return whole;  // several ranges: we may ignore the header
  const auto dash = spec.find('-');
  if (dash == std::string::npos) return whole;
  const auto first = number(spec, 0, dash);
  const auto last = number(spec, dash + 1, spec.size());
  ByteRange r;
  r.kind = ByteRange::Kind::unsatisfiable;
  if (!first) {  // suffix: the last n bytes
    if (!last) return whole;
    if (*last == 0 || size == 0) return r;
    r.kind = ByteRange::Kind::partial;
    r.length = std::min(*last, size);
    r.first = size - r.length;
    return r;
  }
  if (last && *last < *first) return whole;  // invalid range-spec: ignored
  if (*first >= size) return r;
  r.kind = ByteRange::Kind::partial;
  r.first = *first;
  const std::uint64_t end = last ? std::min(*last, size - 1) : size - 1;
  r.length = end - *first + 1;
  return r;
}

}  // namespace stoss::server::http
