// The bearer token: the system shall read it from its file and accept exactly "Bearer <token>".
#include <gtest/gtest.h>

#include <fstream>

#include "server/http/auth.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::server {
namespace {

TEST(BearerAuth, ReadsTheTokenFileAndComparesTheHeader) {
  test::TempDir dir;
  std::ofstream(dir.path() / "token") << "  s3cret-token \n";
  const auto auth = http::BearerAuth::from_file(dir.path() / "token");
  httplib::Request req;
  EXPECT_FALSE(auth.allows(req));
  req.set_header("Authorization", "Bearer s3cret-token");
  EXPECT_TRUE(auth.allows(req));
  httplib::Request wrong;
  wrong.set_header("Authorization", "Bearer s3cret-tokeN");
  EXPECT_FALSE(auth.allows(wrong));
  httplib::Request basic;
  basic.set_header("Authorization", "Basic s3cret-token");
  EXPECT_FALSE(auth.allows(basic));
  std::ofstream(dir.path() / "empty") << "\n";
  EXPECT_THROW(http::BearerAuth::from_file(dir.path() / "empty"), std::runtime_error);
  EXPECT_THROW(http::BearerAuth::from_file(dir.path() / "missing"), std::runtime_error);
}

}  // namespace
}  // namespace stoss::server
