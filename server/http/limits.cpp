#include "server/http/limits.hpp"

#include <malloc.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "server/http/scene_check.hpp"

namespace stoss::server::http {

namespace {

double number_at(const nlohmann::json& j, const char* key) {
  if (!j.is_object()) return 0;
  auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

/// A JSON count as a 64-bit integer: truncated, negative as 0, beyond 64 bits as LLONG_MAX.
long long count_of(double x) {
  if (!(x > 0)) return 0;
  return x < 9.2e18 ? static_cast<long long>(x) : LLONG_MAX;
}

long long saturating_multiply(long long a, long long b) {
  long long product = 0;
  return __builtin_mul_overflow(a, b, &product) ? LLONG_MAX : product;
}

long long saturating_add(long long a, long long b) {
  long long sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? LLONG_MAX : sum;
}

/// Nodes a mesh description will produce, from its parameters: exact for generators (a box has
/// Π (divisions + 1), a hollow sphere (6 d² + 2)(layers + 1): each node layer is the cube-sphere's surface
/// grid of docs/theory.md §7) and inline meshes; 0 for mesh files, counted when read.
long long estimated_nodes(const nlohmann::json& mesh) {
  if (!mesh.is_object()) return 0;
  if (auto box = mesh.find("box"); box != mesh.end() && box->is_object()) {
    auto d = box->find("divisions");
    if (d == box->end() || !d->is_array()) return 0;
    long long n = 1;
    for (const auto& di : *d)
      n = saturating_multiply(n, di.is_number() ? saturating_add(count_of(di.get<double>()), 1) : 1);
    return n;
  }
  if (auto sphere = mesh.find("hollow_sphere"); sphere != mesh.end()) {
    const long long d = count_of(number_at(*sphere, "divisions"));
    const long long layers = count_of(number_at(*sphere, "layers"));
    const long long per_layer = saturating_add(saturating_multiply(6, saturating_multiply(d, d)), 2);
    return saturating_multiply(per_layer, saturating_add(layers, 1));  // (6 d² + 2)(layers + 1)
  }
  if (auto nodes = mesh.find("nodes"); nodes != mesh.end() && nodes->is_array())
    return static_cast<long long>(nodes->size());
  return 0;
}

/// A body as it arrives, in blocks of at most block_bytes: growing it never copies what it holds (a
/// doubling buffer holds its old and its new copy at once, and glibc keeps the freed smaller copies: the
/// peak was twice the limit). join() frees each block once it is copied: the peak is the body plus a block.
class BodyBlocks {
 public:
  void append(const char* data, std::size_t length) {
    while (length > 0) {
      if (blocks_.empty() || blocks_.back().size() == block_bytes) {
        blocks_.emplace_back();
        if (blocks_.size() > 1) blocks_.back().reserve(block_bytes);  // the first grows with a small body
      }
      const std::size_t take = std::min(length, block_bytes - blocks_.back().size());
      blocks_.back().append(data, take);
      data += take, length -= take, size_ += take;
    }
  }
  /// Frees the blocks of a body that is refused; when they were many, gives the memory back to the
  /// system (glibc keeps freed blocks in the arena of the thread that read them: a flood on every HTTP
  /// thread would otherwise keep the limit's worth in each).
  void release() {
    const bool large = blocks_.size() > 1;
    std::vector<std::string>().swap(blocks_);
    if (large) malloc_trim(0);
  }
  std::string join() && {
    if (blocks_.size() == 1) return std::move(blocks_.front());
    std::string body;
    body.reserve(size_);
    for (std::string& block : blocks_) {
      body += block;
      std::string().swap(block);
    }
    return body;
  }

 private:
  static constexpr std::size_t block_bytes = 1 << 20;
  std::vector<std::string> blocks_;
  std::size_t size_ = 0;
};

}  // namespace

SceneCounts estimate_scene_counts(const nlohmann::json& scene) {
  SceneCounts s;
  if (!scene.is_object()) return s;
  if (auto bodies = scene.find("bodies"); bodies != scene.end() && bodies->is_array())
    for (const auto& body : *bodies)
      if (body.is_object() && body.contains("mesh"))
        s.nodes = saturating_add(s.nodes, estimated_nodes(body["mesh"]));
  model::OutputSpec output;
  const auto o = scene.find("output");
  if (o != scene.end() && number_at(*o, "every") >= 1)
    output.every = static_cast<int>(std::min(number_at(*o, "every"), double(INT_MAX)));
  if (o != scene.end() && number_at(*o, "interval") > 0) output.interval = number_at(*o, "interval");
  double end = 0;
  if (auto time = scene.find("time"); time != scene.end()) {
    // With time.tolerance at most end/min_step steps (min_step defaults to step/1024); with frames at an
    // interval, end/interval + 1 frames.
    end = number_at(*time, "end");
    const double step = number_at(*time, "step");
    std::optional<double> min_step;
    if (time->is_object() && time->contains("tolerance"))
      min_step = number_at(*time, "min_step") > 0 ? number_at(*time, "min_step") : step / 1024;
    s.steps = model::step_bound(end, step, min_step, output.interval);
  }
  s.frames = s.steps > 0 ? output.frame_count(s.steps, end) : 0;
  return s;
}

std::optional<Problem> check_scene_limits_early(const nlohmann::json& scene, const Limits& limits) {
  // Generated and inline meshes are counted exactly before anything is built: a sphere over max_nodes is
  // refused without generating it.
  return check_scene_limits(estimate_scene_counts(scene), limits);
}

std::optional<Problem> check_scene_limits(const scene::Summary& scene, const Limits& limits) {
  return check_scene_limits(SceneCounts{scene.nodes, scene.steps, scene.frames}, limits);
}

std::optional<Problem> check_scene_limits(const SceneCounts& scene, const Limits& limits) {
  nlohmann::json exceeded = nlohmann::json::array();
  std::string detail;
  auto check = [&](const char* name, long long value, long long limit, const char* what) {
    if (value <= limit) return;
    exceeded.push_back({{"name", name}, {"limit", limit}, {"value", value}});
    if (!detail.empty()) detail += "; ";
    detail += std::string("the scene has ") + std::to_string(value) + " " + what +
              ", more than the server limit " + name + " = " + std::to_string(limit);
  };
  check("max_nodes", scene.nodes, limits.max_nodes, "nodes");
  check("max_steps", scene.steps, limits.max_steps, "time steps");
  check("max_frames", scene.frames, limits.max_frames, "output frames");
  if (exceeded.empty()) return std::nullopt;
  return Problem{413,
                 "urn:stoss:problem:limit-exceeded",
                 "Scene exceeds a server limit",
                 detail,
                 {{"limits", exceeded}}};
}

Problem request_too_slow(std::chrono::milliseconds request_timeout, std::uint64_t received) {
  const double seconds = static_cast<double>(request_timeout.count()) / 1000;
  std::string limit = std::to_string(seconds);
  limit.erase(limit.find_last_not_of('0') + 1);
  if (limit.back() == '.') limit.pop_back();
  return {408,
          "urn:stoss:problem:request-timeout",
          "Request Timeout",
          "the body was still arriving " + limit + " s after the request's head (" +
              std::to_string(received) +
              " bytes by then), more than the server limit request_timeout (--request-timeout) allows; "
              "the connection is closed",
          {{"limits", nlohmann::json::array({{{"name", "request_timeout"}, {"limit", seconds}}})}}};
}

std::string read_body_within_limits(const httplib::ContentReader& reader, const Limits& limits,
                                    std::chrono::steady_clock::time_point deadline,
                                    const httplib::Response& res) {
  BodyBlocks blocks;
  std::uint64_t received = 0;
  enum class Stop { no, too_large, too_slow } stop = Stop::no;
  const bool complete = reader([&](const char* data, std::size_t length) {
    received += length;
    if (received > limits.max_body_bytes) return stop = Stop::too_large, false;
    if (std::chrono::steady_clock::now() > deadline) return stop = Stop::too_slow, false;
    blocks.append(data, length);
    return true;
  });
  if (complete) return std::move(blocks).join();
  blocks.release();
  // Unread past the limit, the size is unknown (a Content-Length above it is refused before reading).
  if (stop == Stop::too_large) throw ProblemError(body_too_large(limits.max_body_bytes, std::nullopt));
  if (stop == Stop::too_slow) throw ProblemError(request_too_slow(limits.request_timeout, received));
  if (res.status == 415)
    throw ProblemError(Problem{415, "urn:stoss:problem:unsupported-content-encoding",
                               "Unsupported Media Type",
                               "the body's Content-Encoding cannot be decoded; send it unencoded"});
  throw ProblemError(Problem{400, "urn:stoss:problem:unreadable-body", "Bad Request",
                             "the body could not be read: it ended before its Content-Length or its chunked "
                             "framing is broken (" +
                                 std::to_string(received) + " bytes read)"});
}

}  // namespace stoss::server::http
