// The command line under bad input (issue 10): help on stdout, every unusable scene an exit 2 with a
// message (never an abort), and no silent overwrite of an earlier result.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

std::string write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

TEST(CliHardening, HelpGoesToStdoutWithExit0) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"--help"}, {"validate", "--help"}, {"run", "--help"}, {"study", "--help"}, {"serve", "--help"}}) {
    const auto r = run_stoss(args);
    EXPECT_EQ(r.exit_code, 0) << args[0] << " " << r.err;
    EXPECT_NE(r.out.find("usage: stoss"), std::string::npos) << args[0] << ": " << r.out;
  }
  const auto unknown = run_stoss({"frobnicate"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown command"), std::string::npos);
}

TEST(CliHardening, UnusableScenesAreExit2NeverAnAbort) {
  TempDir dir;
  nlohmann::json bar =
      nlohmann::json::parse(std::ifstream(std::string(STOSS_SOURCE_DIR) + "/api/examples/tumbling_bar.json"));
  std::string every = bar.dump();
  every.replace(every.find("\"every\":4"), 9, "\"every\":4294967296");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"1e400", R"({"format": "stoss-scene/1", "output": {"every": 1e400}})"},
      {"deep", std::string(100'000, '[') + std::string(100'000, ']')},
      {"utf8", "{\"format\": \"stoss-scene/1\", \"name\": \"\xe2\x82\"}"},
      {"every", every},
      {"garbage", std::string("\x00\xff{", 3)}};
  for (const auto& [name, text] : cases) {
    const std::string path = write_file(dir.path() / (name + ".json"), text);
    for (const auto& args :
         std::vector<std::vector<std::string>>{{"validate", path},
                                               {"validate", path, "--json"},
                                               {"run", path, "-o", (dir.path() / "o").string()}}) {
      const auto r = run_stoss(args);
      EXPECT_EQ(r.signal, 0) << name << " " << args[0];
      EXPECT_EQ(r.exit_code, 2) << name << " " << args[0] << ": " << r.out << r.err;
    }
  }
  const auto r = run_stoss({"validate", (dir.path() / "every.json").string()});
  EXPECT_NE(r.err.find("/output/every"), std::string::npos) << r.err;
  const auto j = run_stoss({"validate", (dir.path() / "utf8.json").string(), "--json"});
  EXPECT_NO_THROW((void)nlohmann::json::parse(j.out)) << j.out;
}

TEST(CliHardening, RunWithoutOutputDirectoryRefusesANonEmptyOut) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "out");
  write_file(dir.path() / "out/keep.txt", "earlier result");
  const std::string scene = std::string(STOSS_SOURCE_DIR) + "/api/examples/tumbling_bar.json";
  const auto refused = run_stoss({"run", scene}, std::chrono::seconds(60), dir.path());
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("not empty"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out/result.h5"));
  // An explicit -o out overwrites, as asked.
  const auto forced = run_stoss({"run", scene, "-o", "out"}, std::chrono::seconds(120), dir.path());
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out/result.h5"));
  // Without -o into a fresh directory: out/ is created.
  std::filesystem::remove_all(dir.path() / "out");
  const auto fresh = run_stoss({"run", scene}, std::chrono::seconds(120), dir.path());
  EXPECT_EQ(fresh.exit_code, 0) << fresh.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out/result.h5"));
}

}  // namespace
}  // namespace stoss::test
