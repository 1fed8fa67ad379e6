#include "core/solve/petsc_solver.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

namespace stoss::solve {
namespace {

/// The symbol core/solve/petsc/petsc_amg_solver.cpp exports.
using Factory = AmgSolver* (*)();
constexpr const char* factory_symbol = "stoss_make_petsc_amg_solver";
constexpr const char* module_name = "libstoss_petsc.so";

/// Where the module is: beside the running executable (an installed or copied build), else where
/// the build put it (STOSS_PETSC_MODULE, an absolute path known at configure time).
std::vector<std::string> module_candidates() {
  std::vector<std::string> paths;
  std::error_code error;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) paths.push_back((exe.parent_path() / module_name).string());
#ifdef STOSS_PETSC_MODULE
  paths.push_back(STOSS_PETSC_MODULE);
#endif
  return paths;
}

Factory load_factory() {
  std::string errors;
  for (const std::string& path : module_candidates()) {
    if (!std::filesystem::exists(path)) {
      errors += " " + path + ": not found;";
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept open for the process
    if (!handle) {
      errors += " " + path + ": " + dlerror() + ";";
      continue;
    }
    if (auto factory = reinterpret_cast<Factory>(dlsym(handle, factory_symbol))) return factory;
    errors += " " + path + ": no symbol " + factory_symbol + ";";
  }
  throw std::runtime_error("solver.linear petsc_gamg: cannot load the PETSc module (" +
                           std::string(module_name) + "):" + errors +
                           " install petsc-dev (deploy/packages.txt) and rebuild");
}

}  // namespace

std::unique_ptr<AmgSolver> make_petsc_amg_solver() {
  static std::once_flag once;
  static Factory factory = nullptr;
  std::call_once(once, [] { factory = load_factory(); });
  return std::unique_ptr<AmgSolver>(factory());
}

}  // namespace stoss::solve
