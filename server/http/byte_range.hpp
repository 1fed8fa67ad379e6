#pragma once
/// @file The Range header of a GET on a file (RFC 9110 §14): one byte range, clamped to the file.

#include <cstdint>
#include <string>

namespace stoss::server::http {

struct ByteRange {
  enum class Kind {
    whole,          ///< no Range header, a range unit other than bytes, or several ranges: 200, all
    partial,        ///< 206 with Content-Range: bytes first-last/size
    unsatisfiable,  ///< 416 with Content-Range: bytes */size
  };
  Kind kind = Kind::whole;
  std::uint64_t first = 0;   ///< partial: offset of the first byte
  std::uint64_t length = 0;  ///< partial: bytes to send (≥ 1, first + length ≤ size)
};

/// Resolves `header` (the Range field value, "" when absent) against a file of `size` bytes:
/// "bytes=a-b" (b clamped to size − 1), "bytes=a-", "bytes=-n" (the last n bytes, all of them when
/// n ≥ size). A first byte at or beyond the end, a suffix of 0 bytes, or any range of an empty file is
/// unsatisfiable. A header that does not parse, or asks for several ranges, is ignored (the whole file).
ByteRange resolve_range(const std::string& header, std::uint64_t size);

}  // namespace stoss::server::http
