#pragma once
/// @file JobId: a job's name — 128 random bits as 32 lowercase hex digits, validated before any use.

#include <optional>
#include <string>
#include <string_view>

namespace stoss::server::jobs {

/// A job identifier that is known to match ^[0-9a-f]{32}$. The only way to get one is `random()`
/// or `parse()`, so a JobId is always safe to put into a path or an SQL parameter.
class JobId {
 public:
  /// 128 bits from std::random_device, as 32 lowercase hex digits.
  static JobId random();
  /// The id if `text` has exactly the id format, otherwise nullopt (no lookup happens).
  static std::optional<JobId> parse(std::string_view text);

  const std::string& str() const { return text_; }
  bool operator==(const JobId& other) const = default;
  bool operator<(const JobId& other) const { return text_ < other.text_; }

 private:
  explicit JobId(std::string text) : text_(std::move(text)) {}
  std::string text_;
};

}  // namespace stoss::server::jobs
