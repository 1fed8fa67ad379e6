// problem+json (RFC 9457): the system shall answer errors as problem documents, even for invalid UTF-8.
#include <gtest/gtest.h>

#include "server/http/problem.hpp"

namespace stoss::server {
namespace {

TEST(Problem, IsRfc9457JsonAndSurvivesInvalidUtf8) {
  http::Problem p{422,
                  "urn:stoss:problem:invalid-scene",
                  "Invalid scene",
                  "bad \xff byte",
                  {{"errors", nlohmann::json::array()}}};
  httplib::Response res;
  p.write(res);
  EXPECT_EQ(res.status, 422);
  EXPECT_EQ(res.get_header_value("Content-Type"), "application/problem+json");
  const nlohmann::json j = nlohmann::json::parse(res.body);
  EXPECT_EQ(j["type"], "urn:stoss:problem:invalid-scene");
  EXPECT_EQ(j["status"], 422);
  EXPECT_TRUE(j["errors"].is_array());
}

}  // namespace
}  // namespace stoss::server
