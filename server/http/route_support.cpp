#include "server/http/route_support.hpp"

#include <malloc.h>

#include <atomic>
#include <fstream>
#include <memory>

#include "server/http/byte_range.hpp"
#include "server/http/problem.hpp"
#include "server/meshes/mesh_store.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

/// Gives freed memory back to the system (malloc_trim) when the last copy of a request's MeshFiles goes, if
/// the request used a stored mesh: the model built to check a scene on a large mesh frees hundreds of MB
/// that glibc would otherwise keep (docs/measurements.md, "Hardening numbers").
struct TrimAfterUse {
  std::atomic<bool> used{false};
  ~TrimAfterUse() {
    if (used) malloc_trim(0);
  }
};

}  // namespace

[[noreturn]] void fail(int status, const std::string& kind, const std::string& title,
                       const std::string& detail) {
  throw ProblemError(Problem{status, "urn:stoss:problem:" + kind, title, detail});
}

void send_json(Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(dump(body), json_type);
}

jobs::Job find_job(App& app, const Request& req) {
  auto id = jobs::JobId::parse(req.matches[1].str());
  if (!id) fail(404, "unknown-job", "Unknown job", "no such job (job ids are 32 lowercase hex digits)");
  auto job = app.store.get(*id);
  if (!job) fail(404, "unknown-job", "Unknown job", "no job " + id->str());
  return *job;
}

scene::MeshFiles mesh_files(App& app) {
  scene::MeshFiles files = app.files.mesh_files();
  files.parsed = [store = &meshes::MeshStore::at(app.files.meshes()),
                  limits = mesh::upload_limits(app.limits.max_nodes),
                  trim = std::make_shared<TrimAfterUse>()](const std::string& id) {
    trim->used = true;
    return store->parsed(id, limits);
  };
  return files;
}

std::optional<std::string> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool all_digits(const std::string& text, std::size_t max_length) {
  return !text.empty() && text.size() <= max_length &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::string format_param(const Request& req, const std::vector<std::string>& allowed) {
  const std::string format = req.has_param("format") ? req.get_param_value("format") : allowed.front();
  if (std::find(allowed.begin(), allowed.end(), format) != allowed.end()) return format;
  std::string names;
  for (const auto& name : allowed) names += (names.empty() ? "" : ", ") + name;
  fail(400, "bad-parameter", "Bad parameter", "format must be one of " + names);
}

void stream_file(const Request& req, Response& res, const std::filesystem::path& path,
                 const std::string& type) {
  auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
  std::error_code error;
  const auto size = static_cast<std::uint64_t>(std::filesystem::file_size(path, error));
  if (!*in || error) fail(500, "missing-result", "Result missing", "the result file cannot be read");
  const ByteRange range = resolve_range(req.get_header_value("Range"), size);
  if (range.kind == ByteRange::Kind::unsatisfiable) {
    res.set_header("Content-Range", "bytes */" + std::to_string(size));
    fail(416, "range-not-satisfiable", "Range Not Satisfiable",
         "the file has " + std::to_string(size) + " bytes; Range " + req.get_header_value("Range") +
             " selects none of them");
  }
  const std::uint64_t first = range.kind == ByteRange::Kind::partial ? range.first : 0;
  const std::uint64_t length = range.kind == ByteRange::Kind::partial ? range.length : size;
  res.status = 200;
  if (range.kind == ByteRange::Kind::partial) {
    res.status = 206;
    res.set_header("Content-Range", "bytes " + std::to_string(first) + "-" +
                                        std::to_string(first + length - 1) + "/" + std::to_string(size));
  }
  res.set_content_provider(static_cast<std::size_t>(length), type,
                           [in, first](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                             char buffer[1 << 16];
                             in->seekg(static_cast<std::streamoff>(first + offset));
                             in->read(buffer, static_cast<std::streamsize>(std::min(length, sizeof buffer)));
                             const auto n = in->gcount();
                             return n > 0 && sink.write(buffer, static_cast<std::size_t>(n));
                           });
}

}  // namespace stoss::server::http
