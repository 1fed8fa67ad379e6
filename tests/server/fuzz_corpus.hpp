#pragma once
/// @file A deterministic mutation corpus for fuzzing the scene and study parsers, seeded from
/// api/examples/*.json: the same seed gives the same inputs on every machine, so a failure reproduces.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

namespace stoss::test {

/// One fuzz input: the text, and whether the mutation kept it JSON (structural) or broke bytes.
struct FuzzInput {
  std::string text;
  bool structural = false;
};

class FuzzCorpus {
 public:
  /// Seeds from every api/examples/*.json (scenes) and study bodies made from them.
  explicit FuzzCorpus(std::uint64_t seed = 20261129);

  /// The next scene input: a seed scene with 1–4 structural mutations (values replaced by hostile ones:
  /// 2^32, -1, 1e308, huge strings, wrong types, members removed, arrays grown or emptied, cut UTF-8), or,
  /// one time in four, with bytes mutated (flipped, inserted, truncated, brackets piled up).
  FuzzInput next_scene();
  /// The next study body: {"scene": <mutated scene>, "steps": [...], ...} with mutations of its own.
  FuzzInput next_study();

  std::size_t seeds() const { return scenes_.size(); }

 private:
  nlohmann::json hostile_value();
  void mutate_structure(nlohmann::json& doc, int mutations);
  std::string mutate_bytes(std::string text);
  std::size_t below(std::size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  }

  std::mt19937_64 rng_;
  std::vector<nlohmann::json> scenes_;
};

}  // namespace stoss::test
