// Fuzzing (issue 10): a deterministic mutation corpus seeded from api/examples/*.json goes through the
// scene parser and validator and the study parser in process (100,000 inputs, at least half of them
// JSON that reaches the validator), then a smaller corpus through the live server and through
// `stoss validate` / `stoss run`. Every input gets an answer: a 4xx or exit 2 when invalid, never a crash,
// an abort or a 5xx. STOSS_FUZZ_INPUTS and STOSS_FUZZ_LIVE_INPUTS override the counts (deploy/sanitize.sh).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <future>
#include <map>

#include "server/common/json_input.hpp"
#include "server/http/problem.hpp"
#include "server/http/scene_check.hpp"
#include "server/http/study_check.hpp"
#include "tests/server/fuzz_corpus.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;

std::size_t count_from_env(const char* name, std::size_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  return static_cast<std::size_t>(std::strtoull(text, nullptr, 10));
}

server::http::Limits fuzz_limits() {
  server::http::Limits limits;
  limits.max_nodes = 20'000;  // keeps a mutated generator from building a huge mesh in a unit test
  return limits;
}

TEST(Fuzz, InProcessScenesAndStudiesAlwaysGetAnAnswer) {
  const std::size_t inputs = count_from_env("STOSS_FUZZ_INPUTS", 100'000);
  FuzzCorpus corpus;
  ASSERT_GE(corpus.seeds(), 5u);
  const auto limits = fuzz_limits();
  std::size_t reached_validator = 0, valid = 0, studies = 0;
  std::map<int, std::size_t> statuses;
  for (std::size_t i = 0; i < inputs; ++i) {
    const bool study = i % 5 == 4;
    const FuzzInput input = study ? corpus.next_study() : corpus.next_scene();
    studies += study;
    nlohmann::json doc;
    try {
      doc = server::parse_json_input(input.text);
    } catch (const server::JsonInputError&) {
      ++statuses[400];
      continue;
    }
    ++reached_validator;
    try {
      if (study)
        server::http::check_study(doc, limits);
      else
        server::http::check_scene(doc, limits);
      ++valid;
      ++statuses[200];
    } catch (const server::http::ProblemError& e) {
      const int status = e.problem().status;
      ++statuses[status];
      ASSERT_TRUE(status == 413 || status == 422)
          << "input " << i << ": " << status << " " << e.problem().detail << "\n"
          << input.text.substr(0, 2000);
      (void)server::safe_dump(e.problem().to_json());  // the answer can always be written
    }
    // Any other exception escapes and fails the test; a crash ends it.
  }
  std::cout << "fuzz: " << inputs << " inputs (" << studies << " studies), " << reached_validator
            << " reached the validator, " << valid << " valid; by answer:";
  for (const auto& [status, n] : statuses) std::cout << " " << status << "×" << n;
  std::cout << std::endl;
  EXPECT_GE(reached_validator * 2, inputs);
  EXPECT_GT(valid, 0u);
}

std::string write_input(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

TEST(Fuzz, TheLiveServerAndTheCommandLineAnswerEveryInput) {
  const std::size_t inputs = count_from_env("STOSS_FUZZ_LIVE_INPUTS", 2'000);
  TempDir dir;
  LiveServer server(dir.path() / "data",
                    {"--workers", "0", "--max-nodes", "20000", "--max-queue", "1000000"});
  auto c = server.client();
  FuzzCorpus corpus(7);
  const char* types[] = {"application/json", "application/x-www-form-urlencoded", "text/plain"};
  std::map<int, std::size_t> statuses;
  for (std::size_t i = 0; i < inputs; ++i) {
    const bool study = i % 3 == 2;
    const FuzzInput input = study ? corpus.next_study() : corpus.next_scene();
    const std::string path = study ? "/v1/studies" : i % 3 == 0 ? "/v1/validate" : "/v1/jobs";
    auto r = c.Post(path, input.text, types[i % 3]);
    ASSERT_TRUE(r) << "no answer to input " << i << " (" << path << "): " << input.text.substr(0, 500) << "\n"
                   << server.output();
    ++statuses[r->status];
    EXPECT_TRUE(r->status == 200 || r->status == 201 || (r->status >= 400 && r->status < 500))
        << "input " << i << ": " << r->status << " " << r->body.substr(0, 300);
  }
  ASSERT_TRUE(server.alive()) << server.output();
  EXPECT_EQ(c.Get("/healthz")->status, 200);
  std::cout << "fuzz (live server): " << inputs << " inputs; by status:";
  for (const auto& [status, n] : statuses) std::cout << " " << status << "×" << n;
  std::cout << std::endl;

  // The command line: validate (plain and --json), two processes at a time, and run for a few inputs that
  // validate, with few steps.
  std::map<int, std::size_t> exits;
  std::size_t runs = 0;
  for (std::size_t i = 0; i < inputs; i += 2) {
    FuzzInput pair[2] = {corpus.next_scene(), corpus.next_scene()};
    std::future<CommandResult> results[2];
    for (int k = 0; k < 2; ++k) {
      const std::string file =
          write_input(dir.path() / ("input" + std::to_string(k) + ".json"), pair[k].text);
      const bool json = k == 1;
      results[k] = std::async(std::launch::async, [file, json] {
        return run_stoss(json ? std::vector<std::string>{"validate", file, "--json"}
                              : std::vector<std::string>{"validate", file},
                         60s);
      });
    }
    for (int k = 0; k < 2; ++k) {
      const CommandResult r = results[k].get();
      const FuzzInput& input = pair[k];
      const bool json = k == 1;
      ASSERT_EQ(r.signal, 0) << "stoss validate died of signal " << r.signal << " on input " << i + k << ":\n"
                             << input.text.substr(0, 2000);
      ++exits[r.exit_code];
      ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.exit_code << " " << r.err;
      if (!json) continue;
      nlohmann::json answer;
      ASSERT_NO_THROW(answer = nlohmann::json::parse(r.out)) << r.out;
      EXPECT_EQ(answer["valid"].get<bool>(), r.exit_code == 0) << r.out;
      // A valid, small scene also runs (3 steps): an exit code, never a signal.
      if (r.exit_code == 0 && runs < 25 && answer["nodes"].get<int>() <= 2000) {
        nlohmann::json scene = nlohmann::json::parse(input.text);
        scene["time"]["end"] = scene["time"]["step"].get<double>() * 3;
        const std::string capped = write_input(dir.path() / "run.json", scene.dump());
        const auto ran = run_stoss({"run", capped, "-o", (dir.path() / "out").string()}, 120s);
        ++runs;
        EXPECT_EQ(ran.signal, 0) << "stoss run died on:\n" << scene.dump().substr(0, 2000);
        // 0 success, 1 solver failure, 2 a scene the integrator refuses (e.g. a degenerate element).
        EXPECT_TRUE(ran.exit_code == 0 || ran.exit_code == 1 || ran.exit_code == 2)
            << ran.exit_code << " " << ran.err;
      }
    }
  }
  std::cout << "fuzz (stoss validate): " << inputs << " inputs; by exit code:";
  for (const auto& [code, n] : exits) std::cout << " " << code << "×" << n;
  std::cout << "; " << runs << " of them run" << std::endl;
}

}  // namespace
}  // namespace stoss::test
