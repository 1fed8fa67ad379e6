#include "server/jobs/running/launcher.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace stoss::server::jobs {

namespace {

std::vector<std::string> words_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

bool is_ellipsis(const std::string& word) {
  return word == "…" || word == "...";
}

}  // namespace

std::string default_launcher(bool as_root) {
  return std::string("mpiexec -n {ranks}") + (as_root ? " --allow-run-as-root" : "") +
         " --use-hwthread-cpus --bind-to none";
}

std::optional<std::string> launcher_problem(const std::string& launcher) {
  if (launcher.find_first_of("\"'\\") != std::string::npos)
    return "--launcher takes words split by spaces, without quotes or backslashes, got '" + launcher + "'";
  const auto words = words_of(launcher);
  if (words.empty() || is_ellipsis(words.front()))
    return "--launcher needs a program to run, such as 'mpiexec -n {ranks}', got '" + launcher + "'";
  return std::nullopt;
}

std::vector<std::string> launcher_command(const std::string& launcher, int ranks,
                                          const std::vector<std::string>& command) {
  std::vector<std::string> words = words_of(launcher);
  if (!words.empty() && is_ellipsis(words.back())) words.pop_back();
  for (std::string& word : words)
    for (std::size_t at; (at = word.find("{ranks}")) != std::string::npos;)
      word.replace(at, 7, std::to_string(ranks));
  words.insert(words.end(), command.begin(), command.end());
  return words;
}

std::filesystem::path this_executable() {
  std::error_code error;
  auto executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot find this executable (/proc/self/exe): " + error.message());
  return executable;
}

std::string exec_command(const std::vector<std::string>& command) {
  std::vector<char*> argv;
  for (const std::string& word : command) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);
  execvp(argv[0], argv.data());
  return "cannot start '" + command.front() + "': " + std::strerror(errno);
}

}  // namespace stoss::server::jobs
