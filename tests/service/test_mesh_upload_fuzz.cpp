// Mesh upload fuzzing under an address-space limit (issue 20, "Bounded work for every upload"): crafted .inp
// decks and .msh files, mutations of the committed fixtures and the nine reproducers of the issue rebuilt,
// parsed in process by a forked child whose RLIMIT_AS sits a small margin above its baseline (the bulk),
// then a smaller number posted to a live server, also under RLIMIT_AS (set with prlimit). Every input gets
// an answer: the parse succeeds or is a MeshFileError (422), never std::bad_alloc or another exception, never
// a 5xx, never a signal; no answer echoes a line of /etc/passwd. STOSS_MESH_FUZZ_INPUTS and
// STOSS_MESH_FUZZ_LIVE_INPUTS override the counts.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>

#include "core/mesh/mesh_file.hpp"
#include "server/common/sha256.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

namespace fs = std::filesystem;

const fs::path fixtures = fs::path(STOSS_SOURCE_DIR) / "tests" / "data" / "meshes";

std::size_t count_from_env(const char* name, std::size_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  return static_cast<std::size_t>(std::strtoull(text, nullptr, 10));
}

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// One crafted upload: its bytes and format ("inp" | "msh").
struct MeshInput {
  std::string bytes;
  std::string format;
  std::string name;  ///< what it is, for a failure message
};

const std::string cube =
    "*NODE, NSET=NALL\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
    "*ELEMENT, TYPE=C3D8, ELSET=EALL\n1,1,2,3,4,5,6,7,8\n";

/// The nine reproducers of issue 20, written anew, and their relatives.
std::vector<MeshInput> reproducers() {
  std::vector<MeshInput> out;
  const auto add = [&](std::string name, std::string bytes, std::string format = "inp") {
    out.push_back({std::move(bytes), std::move(format), std::move(name)});
  };
  add("GENERATE up to 2^63-1", "*NSET, NSET=ALL, GENERATE\n1, 9223372036854775807, 1\n");
  std::string lines = "*ELSET, ELSET=BIG, GENERATE\n";
  for (int i = 0; i < 100; ++i) lines += "1, 10000000\n";
  add("100 lines of 10 M ids", lines);
  std::string doubling = cube + "*ELSET, ELSET=D\n1\n";
  for (int i = 0; i < 24; ++i) doubling += "*ELSET, ELSET=D\nD, D\n";
  add("a set doubling itself 24 times", doubling);
  add("*INCLUDE of /dev/urandom", "*NODE\n*INCLUDE, INPUT=/dev/urandom\n");
  add("*INCLUDE of /dev/zero", cube + "*INCLUDE, INPUT=/dev/zero\n");
  add("*INCLUDE of /etc/passwd under *SURFACE", cube + "*SURFACE, NAME=S\n*INCLUDE, INPUT=/etc/passwd\n");
  add("*INCLUDE of ../jobs.db", cube + "*INCLUDE, INPUT=../jobs.db\n");
  add("*INCLUDE of /proc/self/cmdline", "*NODE\n*INCLUDE, INPUT=/proc/self/cmdline\n");
  const std::string stored_id = server::sha256_hex(cube);
  std::string chain;
  for (int i = 0; i < 1000; ++i) chain += "*INCLUDE, INPUT=" + stored_id + ".inp\n";
  add("a chain of includes of a stored mesh", chain);
  add("nested includes", "*INCLUDE, INPUT=\"a.inp\"\n");
  // 2,000 rows each expanding a set of 1,000 elements: 2 M faces from 60 KB.
  add("surface rows expanding a large set", [] {
    std::string deck = cube.substr(0, cube.find("*ELEMENT")) + "*ELEMENT, TYPE=C3D8, ELSET=EALL\n";
    for (int e = 1; e <= 1000; ++e) deck += std::to_string(e) + ",1,2,3,4,5,6,7,8\n";
    deck += "*SURFACE, NAME=S\n";
    for (int i = 0; i < 2000; ++i) deck += "EALL, S1\n";
    return deck;
  }());
  add("nodes header of 2^40",
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1099511627776 1 1099511627776\n", "msh");
  add("entities header of 2^40", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n1099511627776 0 0 0\n",
      "msh");
  add("a line of 10 M commas", cube + "*NSET, NSET=C\n" + std::string(10'000'000, ',') + "\n");
  return out;
}

/// Deterministic mutations of the fixtures: bytes flipped, ranges cut or repeated, numbers replaced by
/// hostile ones, hostile keyword lines inserted, files truncated.
class MeshCorpus {
 public:
  explicit MeshCorpus(std::uint64_t seed) : rng_(seed) {
    seeds_.push_back({bytes_of(fixtures / "two_blocks_ascii.msh"), "msh", "two_blocks_ascii.msh"});
    seeds_.push_back({bytes_of(fixtures / "two_blocks_binary.msh"), "msh", "two_blocks_binary.msh"});
    seeds_.push_back({bytes_of(fixtures / "cgx_block.inp"), "inp", "cgx_block.inp"});
    seeds_.push_back(
        {cube + "*SURFACE, NAME=TOP\nEALL, S2\n*NSET, NSET=G, GENERATE\n1, 8, 1\n", "inp", "cube"});
  }

  MeshInput next() {
    MeshInput input = seeds_[below(seeds_.size())];
    const int mutations = 1 + static_cast<int>(below(3));
    for (int m = 0; m < mutations; ++m) mutate(input);
    input.name = "mutation of " + input.name;
    return input;
  }

 private:
  std::size_t below(std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  }

  std::size_t line_start(const std::string& text) {
    const std::size_t at = below(text.size() + 1);
    const std::size_t newline = text.rfind('\n', at == 0 ? 0 : at - 1);
    return at == 0 || newline == std::string::npos ? 0 : newline + 1;
  }

  void mutate(MeshInput& input) {
    std::string& t = input.bytes;
    static const char* numbers[] = {
        "9223372036854775807",  "-1",         "0",     "4294967296",          "1e308", "1e-320", "nan",
        "99999999999999999999", "2147483648", "1e200", "-9223372036854775808"};
    static const char* inp_lines[] = {"*INCLUDE, INPUT=/etc/passwd\n",
                                      "*INCLUDE, INPUT=../jobs.db\n",
                                      "*INCLUDE, INPUT=/dev/zero\n",
                                      "*INCLUDE, INPUT=/dev/urandom\n",
                                      "*INCLUDE, INPUT=/proc/self/cmdline\n",
                                      "*NSET, NSET=X, GENERATE\n1, 9223372036854775807\n",
                                      "*ELSET, ELSET=EALL\nEALL, EALL, EALL, EALL\n",
                                      "*SURFACE, NAME=S\nEALL, S1\nEALL, S2\n",
                                      "*ELEMENT, TYPE=C3D8\n",
                                      "*NODE\n",
                                      ",,,,,,,,\n"};
    static const char* msh_lines[] = {"$Nodes\n1 1099511627776 1 1099511627776\n",
                                      "$Entities\n1099511627776 0 0 0\n",
                                      "$Elements\n1 2147483647 1 2147483647\n",
                                      "$PhysicalNames\n1000000000\n",
                                      "$EndNodes\n",
                                      "3 1 5 1000000\n"};
    if (t.empty()) return;
    switch (below(7)) {
      case 0:  // flip a byte
        t[below(t.size())] = static_cast<char>(below(256));
        break;
      case 1: {  // cut a range
        const std::size_t at = below(t.size());
        t.erase(at, 1 + below(64));
        break;
      }
      case 2: {  // repeat a line up to 50 times
        const std::size_t at = line_start(t);
        const std::size_t end = std::min(t.find('\n', at), t.size());
        const std::string line = t.substr(at, end - at + 1);
        std::string repeated;
        for (std::size_t k = 0, n = 1 + below(50); k < n; ++k) repeated += line;
        t.insert(at, repeated);
        break;
      }
      case 3: {  // a number replaced by a hostile one
        std::size_t at = below(t.size());
        while (at < t.size() && !std::isdigit(static_cast<unsigned char>(t[at]))) ++at;
        std::size_t end = at;
        while (end < t.size() && (std::isdigit(static_cast<unsigned char>(t[end])) || t[end] == '.' ||
                                  t[end] == 'e' || t[end] == '-' || t[end] == '+'))
          ++end;
        t.replace(at, end - at, numbers[below(std::size(numbers))]);
        break;
      }
      case 4:  // a hostile line
        t.insert(line_start(t), input.format == "inp" ? inp_lines[below(std::size(inp_lines))]
                                                      : msh_lines[below(std::size(msh_lines))]);
        break;
      case 5:  // truncated
        t.resize(below(t.size()));
        break;
      default: {  // 8 bytes of 0xff (a size_t of 2^64 - 1 in a binary file)
        const std::size_t at = below(t.size());
        t.replace(at, std::min<std::size_t>(8, t.size() - at), std::string(8, '\xff'));
      }
    }
  }

  std::mt19937_64 rng_;
  std::vector<MeshInput> seeds_;
};

/// The address space (VmSize or VmPeak, bytes) of process `pid` ("self" for this one).
std::size_t vm_bytes(const std::string& pid, const std::string& field) {
  std::ifstream in("/proc/" + pid + "/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stoull(line.substr(field.size() + 1)) * 1024;
  return 0;
}

/// What the child reports through its pipe: counts, the peak, and the first failure (empty when none).
struct ChildReport {
  std::size_t parsed = 0, refused = 0;
  std::size_t baseline = 0, peak = 0, limit = 0;
  char failure[2048] = {};
};

constexpr std::size_t margin = std::size_t(128) << 20;  ///< RLIMIT_AS above the child's baseline
constexpr long long fuzz_max_nodes = 200'000;           ///< the server's default --max-nodes

/// Parses every input in this (forked) process under RLIMIT_AS = baseline + margin; fills `report`.
void parse_all_under_limit(std::size_t inputs, ChildReport& report) {
  MeshCorpus corpus(20261202);
  const std::vector<MeshInput> fixed = reproducers();
  const mesh::ReadLimits limits = mesh::upload_limits(fuzz_max_nodes);
  report.baseline = vm_bytes("self", "VmSize");
  report.limit = report.baseline + margin;
  const rlimit cap{report.limit, report.limit};
  setrlimit(RLIMIT_AS, &cap);
  for (std::size_t i = 0; i < inputs; ++i) {
    const MeshInput input = i < fixed.size() ? fixed[i] : corpus.next();
    try {
      const mesh::ImportedMesh m = mesh::parse_mesh_bytes(input.bytes, input.format, "request body", limits);
      if (!m.hex8.empty()) (void)mesh::select_body(m, std::nullopt);
      ++report.parsed;
      if (i < fixed.size())
        std::snprintf(report.failure, sizeof report.failure, "reproducer '%s' was accepted",
                      input.name.c_str());
    } catch (const mesh::MeshFileError& e) {
      ++report.refused;
      if (std::string(e.what()).find("root:") != std::string::npos)
        std::snprintf(report.failure, sizeof report.failure, "input %zu (%s) echoes /etc/passwd: %s", i,
                      input.name.c_str(), e.what());
    } catch (const std::exception& e) {
      std::snprintf(report.failure, sizeof report.failure, "input %zu (%s): %s: %s", i, input.name.c_str(),
                    typeid(e).name(), e.what());
    }
    if (report.failure[0]) break;
  }
  report.peak = vm_bytes("self", "VmPeak");
}

TEST(MeshFuzz, EveryCraftedUploadIsParsedOrRefusedWithinASmallAddressSpace) {
  const std::size_t inputs = count_from_env("STOSS_MESH_FUZZ_INPUTS", 60'000);
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(fds[0]);
    auto* report = new ChildReport;
    parse_all_under_limit(inputs, *report);
    const bool ok = write(fds[1], report, sizeof *report) == static_cast<ssize_t>(sizeof *report);
    _exit(ok ? 0 : 3);
  }
  close(fds[1]);
  ChildReport report;
  const ssize_t got = read(fds[0], &report, sizeof report);
  close(fds[0]);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the parsing child died of signal " << WTERMSIG(status);
  ASSERT_EQ(got, static_cast<ssize_t>(sizeof report));
  EXPECT_STREQ(report.failure, "");
  EXPECT_EQ(report.parsed + report.refused, inputs);
  EXPECT_LE(report.peak, report.limit);
  EXPECT_GT(report.parsed, inputs / 20) << "the mutations should leave some files usable";
  std::cout << "mesh fuzz (in process): " << inputs << " inputs, " << report.parsed << " parsed, "
            << report.refused << " refused (422); address space " << report.baseline / (1 << 20)
            << " MiB at start, peak " << report.peak / (1 << 20) << " MiB, limit " << report.limit / (1 << 20)
            << " MiB" << std::endl;
}

TEST(MeshFuzz, TheLiveServerAnswersEveryCraftedUploadWithinItsAddressSpaceLimit) {
  const std::size_t inputs = count_from_env("STOSS_MESH_FUZZ_LIVE_INPUTS", 3'000);
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});
  auto c = server.client();
  // A symbolic link in the upload folder, and a stored mesh whose id a deck might include.
  fs::create_directories(dir.path() / "data" / "meshes");
  fs::create_symlink("/etc/passwd", dir.path() / "data" / "meshes" / "passwd.inp");
  ASSERT_EQ(c.Post("/v1/meshes", cube, "application/octet-stream")->status, 201);
  const std::string pid = std::to_string(server.pid());
  const std::size_t baseline = vm_bytes(pid, "VmSize");
  const std::size_t limit = baseline + 2 * margin;  // two malloc arenas (M_ARENA_MAX) reserve 64 MiB each
  const rlimit cap{limit, limit};
  ASSERT_EQ(prlimit(server.pid(), RLIMIT_AS, &cap, nullptr), 0);

  std::vector<MeshInput> fixed = reproducers();
  fixed.push_back(
      {"*NODE\n*INCLUDE, INPUT=passwd.inp\n", "inp", "*INCLUDE of a symbolic link in the upload folder"});
  MeshCorpus corpus(7);
  std::map<int, std::size_t> statuses;
  for (std::size_t i = 0; i < inputs; ++i) {
    const MeshInput input = i < fixed.size() ? fixed[i] : corpus.next();
    auto r = c.Post(("/v1/meshes?format=" + input.format).c_str(), input.bytes, "application/octet-stream");
    ASSERT_TRUE(r) << "no answer to input " << i << " (" << input.name << ")\n" << server.output();
    ++statuses[r->status];
    // 400: a mutation that emptied the body or left no format to tell.
    ASSERT_TRUE(r->status == 200 || r->status == 201 || r->status == 400 || r->status == 413 ||
                r->status == 422)
        << "input " << i << " (" << input.name << "): " << r->status << " " << r->body.substr(0, 300);
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << input.name << ": " << r->body.substr(0, 300);
    if (i < fixed.size())
      EXPECT_NE(r->status / 100, 2) << input.name << " was accepted: " << r->body.substr(0, 300);
  }
  ASSERT_TRUE(server.alive()) << server.output();
  const std::size_t peak = vm_bytes(pid, "VmPeak");
  EXPECT_LE(peak, limit);
  std::cout << "mesh fuzz (live server): " << inputs << " uploads; by status:";
  for (const auto& [status, n] : statuses) std::cout << " " << status << "×" << n;
  std::cout << "; address space " << baseline / (1 << 20) << " MiB after start, peak " << peak / (1 << 20)
            << " MiB, limit " << limit / (1 << 20) << " MiB" << std::endl;
}

}  // namespace
}  // namespace stoss::test
