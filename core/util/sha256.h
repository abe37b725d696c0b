// SHA-256 (FIPS 180-4) of a byte string, as lowercase hex: the fingerprint under which a
// study database records the exact protocol text it was run with.
#pragma once

#include <string>
#include <string_view>

namespace handlab::util {

std::string sha256_hex(std::string_view bytes);

}  // namespace handlab::util
