#include "core/solve/petsc_solver.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

namespace stoss::solve {
namespace {

/// The symbols core/solve/petsc/petsc_amg_solver.cpp exports.
using Factory = AmgSolver* (*)();
using Barrier = void (*)();
using Sum = void (*)(double*, long);
using Place = void (*)(int*, int*);
using Partition = bool (*)(int, const int*, const int*, int*);
constexpr const char* factory_symbol = "stoss_make_petsc_amg_solver";
constexpr const char* lu_factory_symbol = "stoss_make_petsc_lu_solver";
constexpr const char* barrier_symbol = "stoss_synchronize_ranks";
constexpr const char* sum_symbol = "stoss_sum_over_ranks";
constexpr const char* place_symbol = "stoss_world_place";
constexpr const char* partition_symbol = "stoss_partition_nodes";
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

/// The module, opened once for the process (and kept open).
void* module() {
  static void* handle = nullptr;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string errors;
    for (const std::string& path : module_candidates()) {
      if (!std::filesystem::exists(path)) {
        errors += " " + path + ": not found;";
        continue;
      }
      if ((handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL))) return;
      errors += " " + path + ": " + dlerror() + ";";
    }
    throw std::runtime_error("solver.linear petsc_gamg: cannot load the PETSc module (" +
                             std::string(module_name) + "):" + errors +
                             " install petsc-dev (deploy/packages.txt) and rebuild");
  });
  return handle;
}

template <class Function>
Function symbol(const char* name) {
  if (auto function = reinterpret_cast<Function>(dlsym(module(), name))) return function;
  throw std::runtime_error(std::string("the PETSc module (") + module_name + ") has no symbol " + name);
}

}  // namespace

std::unique_ptr<AmgSolver> make_petsc_amg_solver() {
  static const Factory factory = symbol<Factory>(factory_symbol);
  return std::unique_ptr<AmgSolver>(factory());
}

std::unique_ptr<AmgSolver> make_petsc_lu_solver() {
  static const Factory factory = symbol<Factory>(lu_factory_symbol);
  return std::unique_ptr<AmgSolver>(factory());
}

void synchronize_ranks() {
  static const Barrier barrier = symbol<Barrier>(barrier_symbol);
  barrier();
}

void sum_over_ranks(double* values, long count) {
  static const Sum sum = symbol<Sum>(sum_symbol);
  sum(values, count);
}

std::vector<int> partition_nodes(const std::vector<int>& offsets, const std::vector<int>& neighbours) {
  static const Partition partition = symbol<Partition>(partition_symbol);
  const int nodes = static_cast<int>(offsets.size()) - 1;
  std::vector<int> parts(nodes);
  if (!partition(nodes, offsets.data(), neighbours.data(), parts.data()))
    throw std::runtime_error("PETSc's partitioner (PT-Scotch) failed on the nodes' graph of the mesh");
  return parts;
}

std::pair<int, int> world_place() {
  static const Place place = symbol<Place>(place_symbol);
  int rank = 0, size = 1;
  place(&rank, &size);
  return {rank, size};
}

}  // namespace stoss::solve
