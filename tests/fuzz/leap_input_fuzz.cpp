// libFuzzer target for what reads untrusted tracker input: the LZ-string decoder, LeapJS
// Playback documents and single Leap WebSocket messages. Any input may be rejected; none may
// crash, hang or trip the sanitizers.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "core/tracking/leap_json.h"
#include "core/tracking/lz_string.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string text;
  try {
    text = handlab::tracking::lz_decompress_base64(input);
  } catch (const handlab::tracking::LzStringError&) {
    text.assign(input);  // not LZ-string: treat the bytes as JSON
  }
  try {
    (void)handlab::tracking::parse_playback(text, "fuzz");
  } catch (const std::runtime_error&) {
  }
  std::string error;
  (void)handlab::tracking::parse_leap_message(input, &error);
  return 0;
}
