#pragma once
/// @file Clock: where the job queue reads the time, so leases and the rescuer can be tested without sleeps.

#include <atomic>
#include <cstdint>
#include <string>

namespace stoss::server::jobs {

/// Milliseconds since the Unix epoch (UTC).
using Millis = std::int64_t;

/// The time source of the store, the rescuer and the workers.
class Clock {
 public:
  virtual ~Clock() = default;
  virtual Millis now() const = 0;
};

/// The wall clock (std::chrono::system_clock).
class SystemClock : public Clock {
 public:
  Millis now() const override;
};

/// A clock that only moves when told to: for tests of leases and the rescuer.
class ManualClock : public Clock {
 public:
  explicit ManualClock(Millis start = 1'700'000'000'000) : now_(start) {}
  Millis now() const override { return now_.load(); }
  void advance(Millis by) { now_ += by; }

 private:
  std::atomic<Millis> now_;
};

/// RFC 3339 UTC timestamp with milliseconds, e.g. "2024-05-01T12:00:00.250Z".
std::string format_rfc3339(Millis t);

}  // namespace stoss::server::jobs
