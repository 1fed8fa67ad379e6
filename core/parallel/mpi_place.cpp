#include "core/parallel/mpi_place.hpp"

#include <cstdlib>
#include <optional>
#include <string>

namespace stoss::parallel {
namespace {

/// A whole non-negative integer, or nothing.
std::optional<int> whole_number(const char* text) {
  if (!text || !*text) return std::nullopt;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0' || value < 0 || value > 1 << 24) return std::nullopt;
  return static_cast<int>(value);
}

std::optional<MpiPlace> place_from(const char* rank_variable, const char* size_variable) {
  const auto rank = whole_number(std::getenv(rank_variable));
  const auto size = whole_number(std::getenv(size_variable));
  if (!rank || !size || *size < 1 || *rank >= *size) return std::nullopt;
  return MpiPlace{*rank, *size};
}

}  // namespace

MpiPlace mpi_place() {
  if (const auto open_mpi = place_from("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE")) return *open_mpi;
  if (const auto pmi = place_from("PMI_RANK", "PMI_SIZE")) return *pmi;
  // A task of srun's (any --mpi): a batch script's own process has SLURM_PROCID but no step task count.
  if (const auto slurm = place_from("SLURM_PROCID", "SLURM_STEP_NUM_TASKS")) return *slurm;
  return MpiPlace{};
}

}  // namespace stoss::parallel
