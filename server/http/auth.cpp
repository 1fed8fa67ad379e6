#include "server/http/auth.hpp"

#include <fstream>
#include <stdexcept>

namespace stoss::server::http {

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

/// Equal strings, in time that depends only on the lengths.
bool equal_constant_time(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

BearerAuth BearerAuth::from_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read token file " + path.string());
  std::string line;
  std::getline(in, line);
  std::string token = trim(line);
  if (token.empty()) throw std::runtime_error("token file " + path.string() + " holds no token");
  return BearerAuth(std::move(token));
}

bool BearerAuth::allows(const httplib::Request& req) const {
  static const std::string scheme = "Bearer ";
  const std::string header = req.get_header_value("Authorization");
  if (header.compare(0, scheme.size(), scheme) != 0) return false;
  return equal_constant_time(trim(header.substr(scheme.size())), token_);
}

}  // namespace stoss::server::http
