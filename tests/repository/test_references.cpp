// The repository shall stand alone: no file cites a document that is not in it (design notes kept
// outside the repository, the prototype). Citations go to docs/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

TEST(Repository, CitesNoDocumentOutsideIt) {
  const fs::path root = STOSS_SOURCE_DIR;
  // Spelled in two pieces so that this file does not match itself.
  const std::vector<std::string> outside = {
      std::string("formulation") + ".md", std::string("service") + ".md", std::string("../") + "shared",
      std::string("shared/") + "design", std::string("reference/") + "prototype"};
  int files = 0;
  for (const char* top : {"core", "server", "tests", "api", "bench", "deploy", "docs", "scripts"}) {
    if (!fs::exists(root / top)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      if (!entry.is_regular_file() || entry.file_size() > 4'000'000) continue;
      const std::string ext = entry.path().extension().string();
      if (ext == ".h5" || ext == ".png" || ext == ".msh" || ext == ".inp" || ext == ".xdmf") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      ++files;
      for (const std::string& s : outside)
        EXPECT_EQ(text.str().find(s), std::string::npos) << entry.path() << " cites " << s;
    }
  }
  for (const char* file : {"README.md", "CMakeLists.txt"}) {
    std::ifstream in(root / file);
    std::stringstream text;
    text << in.rdbuf();
    for (const std::string& s : outside)
      EXPECT_EQ(text.str().find(s), std::string::npos) << file << " cites " << s;
  }
  EXPECT_GT(files, 100);
}

}  // namespace
