// JobId: the system shall name jobs by 128 random bits and refuse any other text before a lookup.
#include <gtest/gtest.h>

#include <set>

#include "server/jobs/id.hpp"

namespace stoss::server {
namespace {

using jobs::JobId;

TEST(JobId, IsThirtyTwoRandomLowercaseHexDigits) {
  std::set<std::string> seen;
  for (int i = 0; i < 1000; ++i) {
    const JobId id = JobId::random();
    EXPECT_TRUE(JobId::parse(id.str())) << id.str();
    seen.insert(id.str());
  }
  EXPECT_EQ(seen.size(), 1000u);
}

TEST(JobId, RejectsAnythingElseBeforeAnyLookup) {
  for (const char* bad : {"", "0123456789abcdef0123456789abcde", "0123456789abcdef0123456789abcdef0",
                          "0123456789ABCDEF0123456789ABCDEF", "../../../../etc/passwd00000000000",
                          "0123456789abcdef0123456789abcde/", "0123456789abcdef0123456789abcd\n0"})
    EXPECT_FALSE(JobId::parse(bad)) << bad;
}

}  // namespace
}  // namespace stoss::server
