// LZ-string decompression (pieroxy's lz-string, decompressFromBase64), as LeapJS Playback
// stores its recordings. The result is UTF-8.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace handlab::tracking {

class LzStringError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws LzStringError (with the position) for characters outside the base64 alphabet,
// truncated input or codes that refer past the dictionary.
std::string lz_decompress_base64(std::string_view input);

}  // namespace handlab::tracking
