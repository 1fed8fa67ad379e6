#pragma once
/// @file BearerAuth: the shared secret of `--token-file`; every route but /healthz requires it.

#include <filesystem>
#include <string>

#include "server/http/httplib.hpp"

namespace stoss::server::http {

class BearerAuth {
 public:
  /// Reads the token from the file's first line (surrounding whitespace ignored).
  /// Throws std::runtime_error when the file cannot be read or holds no token.
  static BearerAuth from_file(const std::filesystem::path& path);

  explicit BearerAuth(std::string token) : token_(std::move(token)) {}

  /// True when the request carries `Authorization: Bearer <token>` (compared in constant time).
  bool allows(const httplib::Request& req) const;

 private:
  std::string token_;
};

}  // namespace stoss::server::http
