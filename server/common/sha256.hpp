#pragma once
/// @file SHA-256 (FIPS 180-4), for the idempotency body hash.

#include <string>
#include <string_view>

namespace stoss::server {

/// SHA-256 of `data` as 64 lowercase hex digits.
std::string sha256_hex(std::string_view data);

}  // namespace stoss::server
