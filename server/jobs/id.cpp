#include "server/jobs/id.hpp"

#include <array>
#include <random>

namespace stoss::server::jobs {

JobId JobId::random() {
  static constexpr char hex[] = "0123456789abcdef";
  thread_local std::random_device device;
  std::string text;
  text.reserve(32);
  for (int word = 0; word < 4; ++word) {
    std::uint32_t bits = device();
    for (int nibble = 0; nibble < 8; ++nibble, bits >>= 4) text.push_back(hex[bits & 0xF]);
  }
  return JobId(std::move(text));
}

std::optional<JobId> JobId::parse(std::string_view text) {
  if (text.size() != 32) return std::nullopt;
  for (char c : text) {
    const bool digit = c >= '0' && c <= '9';
    const bool lower_hex = c >= 'a' && c <= 'f';
    if (!digit && !lower_hex) return std::nullopt;
  }
  return JobId(std::string(text));
}

}  // namespace stoss::server::jobs
