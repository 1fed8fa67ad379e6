// The flags of `stoss serve`: the system shall take every documented flag, keep the documented defaults
// and name the flag that is wrong.
#include <gtest/gtest.h>

#include "server/cli/serve.hpp"

namespace stoss::server {
namespace {

TEST(ServeOptions, HasDocumentedDefaults) {
  const cli::ServeOptions o = cli::parse_serve_options({});
  EXPECT_EQ(o.host, "127.0.0.1");
  EXPECT_EQ(o.port, 8080);
  EXPECT_EQ(o.data, "var");
  EXPECT_EQ(o.pool.workers, 2);
  EXPECT_EQ(o.pool.lease, 10'000);
  EXPECT_EQ(o.pool.renew_every, 2'000);
  EXPECT_EQ(o.limits.max_body_bytes, 16u << 20);
  EXPECT_EQ(o.limits.max_nodes, 200'000);
  EXPECT_EQ(o.limits.max_steps, 100'000);
  EXPECT_EQ(o.limits.max_frames, 2'000);
  EXPECT_EQ(o.limits.max_queued, 1'000);
  EXPECT_EQ(o.limits.max_ranks_per_job, 1);
  EXPECT_EQ(o.pool.ranks_per_job, 1);
  EXPECT_FALSE(o.token_file);
}

TEST(ServeOptions, ParsesEveryFlag) {
  const cli::ServeOptions o = cli::parse_serve_options({"--listen",
                                                        "0.0.0.0:9000",
                                                        "--data",
                                                        "/tmp/x",
                                                        "--workers",
                                                        "4",
                                                        "--token-file",
                                                        "t",
                                                        "--max-body-bytes=1000",
                                                        "--max-nodes",
                                                        "10",
                                                        "--max-steps",
                                                        "20",
                                                        "--max-frames",
                                                        "30",
                                                        "--max-queue",
                                                        "40",
                                                        "--lease-seconds",
                                                        "1.5",
                                                        "--renew-seconds",
                                                        "0.25",
                                                        "--max-attempts",
                                                        "5",
                                                        "--max-ranks-per-job",
                                                        "8",
                                                        "--ranks-per-job=4"});
  EXPECT_EQ(o.host, "0.0.0.0");
  EXPECT_EQ(o.port, 9000);
  EXPECT_EQ(o.data, "/tmp/x");
  EXPECT_EQ(o.pool.workers, 4);
  EXPECT_EQ(*o.token_file, "t");
  EXPECT_EQ(o.limits.max_body_bytes, 1000u);
  EXPECT_EQ(o.limits.max_nodes, 10);
  EXPECT_EQ(o.limits.max_steps, 20);
  EXPECT_EQ(o.limits.max_frames, 30);
  EXPECT_EQ(o.limits.max_queued, 40);
  EXPECT_EQ(o.pool.lease, 1'500);
  EXPECT_EQ(o.pool.renew_every, 250);
  EXPECT_EQ(o.max_attempts, 5);
  EXPECT_EQ(o.limits.max_ranks_per_job, 8);
  EXPECT_EQ(o.pool.ranks_per_job, 4);
}

TEST(ServeOptions, NamesTheFlagThatIsWrong) {
  auto message = [](std::vector<std::string> args) {
    try {
      cli::parse_serve_options(args);
    } catch (const cli::UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({"--wrokers", "2"}), "unknown option '--wrokers'");
  EXPECT_EQ(message({"--workers"}), "--workers needs a value");
  EXPECT_EQ(message({"--workers", "two"}), "--workers needs an integer in [0, 256], got 'two'");
  EXPECT_EQ(message({"--listen", "8080"}), "--listen needs HOST:PORT, got '8080'");
  EXPECT_EQ(message({"--max-ranks-per-job", "0"}),
            "--max-ranks-per-job needs an integer in [1, 4096], got '0'");
  EXPECT_EQ(message({"--ranks-per-job", "4097"}),
            "--ranks-per-job needs an integer in [1, 4096], got '4097'");
  EXPECT_EQ(message({"--ranks-per-job", "2.5"}), "--ranks-per-job needs an integer in [1, 4096], got '2.5'");
  EXPECT_EQ(message({"--lease-seconds", "1", "--renew-seconds", "2"}),
            "--renew-seconds must be shorter than --lease-seconds");
}

}  // namespace
}  // namespace stoss::server
