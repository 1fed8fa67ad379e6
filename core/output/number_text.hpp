#pragma once
/// @file Numbers as text for the XDMF and CSV files. Private to core/output.

#include <charconv>
#include <string>

namespace stoss::output {

/// The shortest text that reads back as exactly `value` ("0.1", "1e-07", "nan").
inline std::string shortest_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace stoss::output
