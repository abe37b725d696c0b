#include "core/tracking/lz_string.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/util/utf8.h"

namespace handlab::tracking {
namespace {

// Reads the stream's bits: 6 per base64 character, most significant first. lz-string
// assembles each code least significant bit first, so a code is the next n stream bits
// reversed; they are taken from a 64-bit accumulator and reversed by table.
class BitReader {
 public:
  explicit BitReader(std::string_view input) : input_(input) {}

  std::uint32_t read(int bits) {
    while (count_ < bits) refill();
    const std::uint64_t stream =
        (accumulator_ >> (count_ - bits)) & ((std::uint64_t(1) << bits) - 1);
    count_ -= bits;
    consumed_ += std::size_t(bits);
    return reverse(std::uint32_t(stream), bits);
  }
  // lz-string stops when it would read a code past the end of the input: that is, when the
  // character holding the next bit lies beyond the input.
  bool exhausted() const { return consumed_ / 6 + 1 > input_.size(); }
  std::size_t index() const { return consumed_ / 6; }

 private:
  void refill() {
    int value = 0;
    if (next_ < input_.size()) {
      value = table()[static_cast<unsigned char>(input_[next_])];
      if (value < 0)
        throw LzStringError("LZ-string: invalid base64 character at offset " +
                            std::to_string(next_));
    }  // past the end JavaScript reads undefined, which gives 0 bits
    ++next_;
    accumulator_ = (accumulator_ << 6) | std::uint64_t(value);
    count_ += 6;
  }
  static const std::array<int, 256>& table() {
    static const std::array<int, 256> t = [] {
      std::array<int, 256> t{};
      t.fill(-1);
      const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=";
      for (int i = 0; i < 65; ++i) t[static_cast<unsigned char>(alphabet[i])] = i;
      return t;
    }();
    return t;
  }
  static std::uint32_t reverse(std::uint32_t x, int bits) {
    static const std::array<std::uint16_t, 65536> rev = [] {
      std::array<std::uint16_t, 65536> r{};
      for (std::uint32_t i = 0; i < 65536; ++i) {
        std::uint32_t v = 0;
        for (int b = 0; b < 16; ++b) v |= ((i >> b) & 1u) << (15 - b);
        r[i] = std::uint16_t(v);
      }
      return r;
    }();
    const std::uint32_t full = (std::uint32_t(rev[x & 0xFFFF]) << 16) | rev[x >> 16];
    return full >> (32 - bits);
  }

  std::string_view input_;
  std::uint64_t accumulator_ = 0;
  int count_ = 0;
  std::size_t next_ = 0;
  std::size_t consumed_ = 0;
};

std::string utf16_to_utf8(const std::vector<char16_t>& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    std::uint32_t c = text[i];
    if (c >= 0xD800 && c < 0xDC00 && i + 1 < text.size() && text[i + 1] >= 0xDC00 &&
        text[i + 1] < 0xE000) {
      c = 0x10000 + ((c - 0xD800) << 10) + (text[i + 1] - 0xDC00);
      ++i;
    }
    util::append_utf8(out, c);
  }
  return out;
}

}  // namespace

std::string lz_decompress_base64(std::string_view input) {
  while (!input.empty() && (input.back() == '\n' || input.back() == '\r' || input.back() == ' '))
    input.remove_suffix(1);
  if (input.empty()) throw LzStringError("LZ-string: empty input");
  BitReader bits(input);
  // Every dictionary entry is a run of the output already written: (offset, length).
  struct Entry {
    std::uint32_t offset, length;
  };
  std::vector<Entry> dictionary(3, Entry{0, 0});
  std::vector<char16_t> out;
  out.reserve(input.size() * 3);
  int enlarge_in = 4, num_bits = 3;

  auto literal = [&](int width) {
    const auto c = char16_t(bits.read(width));
    dictionary.push_back({std::uint32_t(out.size()), 1});
    out.push_back(c);
  };
  switch (bits.read(2)) {
    case 0:
      literal(8);
      break;
    case 1:
      literal(16);
      break;
    default:
      return std::string();
  }
  Entry w = dictionary.back();
  while (true) {
    if (bits.exhausted())
      throw LzStringError("LZ-string: input ends before the end-of-stream code (truncated?)");
    std::uint32_t c = bits.read(num_bits);
    bool fresh_literal = false;
    if (c == 0 || c == 1) {
      // A new literal: its dictionary entry is where it is written just below.
      dictionary.push_back({std::uint32_t(out.size()), 1});
      const auto value = char16_t(bits.read(c == 0 ? 8 : 16));
      c = std::uint32_t(dictionary.size() - 1);
      fresh_literal = true;
      out.push_back(value);
      if (--enlarge_in == 0) enlarge_in = 1 << num_bits++;
    } else if (c == 2) {
      return utf16_to_utf8(out);
    }
    Entry entry;
    if (fresh_literal) {
      entry = dictionary[c];
    } else if (c < dictionary.size()) {
      entry = dictionary[c];
      // The entry lies wholly before the end, so the copy never overlaps itself.
      const std::uint32_t start = std::uint32_t(out.size());
      out.resize(start + entry.length);
      std::copy_n(out.data() + entry.offset, entry.length, out.data() + start);
      entry.offset = start;
    } else if (c == dictionary.size()) {
      // The code being defined right now: w followed by w's first character.
      const std::uint32_t start = std::uint32_t(out.size());
      out.resize(start + w.length + 1);
      std::copy_n(out.data() + w.offset, w.length, out.data() + start);
      out[start + w.length] = out[w.offset];
      entry = {start, w.length + 1};
    } else {
      throw LzStringError("LZ-string: corrupt data near offset " + std::to_string(bits.index()));
    }
    // w + entry[0] is contiguous in the output: entry was written right after w.
    dictionary.push_back({w.offset, w.length + 1});
    if (--enlarge_in == 0) enlarge_in = 1 << num_bits++;
    w = entry;
  }
}

}  // namespace handlab::tracking
