#include "core/tracking/lz_string.h"

#include <array>
#include <cstdint>
#include <vector>

namespace handlab::tracking {
namespace {

// Reads the stream's bits (6 per base64 character, most significant first).
class BitReader {
 public:
  explicit BitReader(std::string_view input) : input_(input) {
    static const std::array<int, 256> table = [] {
      std::array<int, 256> t;
      t.fill(-1);
      const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=";
      for (int i = 0; i < 65; ++i) t[static_cast<unsigned char>(alphabet[i])] = i;
      return t;
    }();
    table_ = &table;
    value_ = value_at(0);
  }

  std::uint32_t read(int bits) {
    std::uint32_t result = 0;
    for (int power = 0; power < bits; ++power) {
      const bool bit = (value_ & position_) != 0;
      position_ >>= 1;
      if (position_ == 0) {
        position_ = 32;
        value_ = value_at(index_++);
      }
      result |= std::uint32_t(bit) << power;
    }
    return result;
  }
  // lz-string stops when it would read a code past the end of the input.
  bool exhausted() const { return index_ > input_.size(); }
  std::size_t index() const { return index_; }

 private:
  int value_at(std::size_t i) const {
    if (i >= input_.size()) return 0;  // JavaScript reads undefined as 0 bits
    const int v = (*table_)[static_cast<unsigned char>(input_[i])];
    if (v < 0)
      throw LzStringError("LZ-string: invalid base64 character at offset " + std::to_string(i));
    return v;
  }
  std::string_view input_;
  const std::array<int, 256>* table_;
  int value_ = 0;
  int position_ = 32;
  std::size_t index_ = 1;
};

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += char(code);
  } else if (code < 0x800) {
    out += char(0xC0 | (code >> 6));
    out += char(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += char(0xE0 | (code >> 12));
    out += char(0x80 | ((code >> 6) & 0x3F));
    out += char(0x80 | (code & 0x3F));
  } else {
    out += char(0xF0 | (code >> 18));
    out += char(0x80 | ((code >> 12) & 0x3F));
    out += char(0x80 | ((code >> 6) & 0x3F));
    out += char(0x80 | (code & 0x3F));
  }
}

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
    append_utf8(out, c);
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
      const std::uint32_t start = std::uint32_t(out.size());
      for (std::uint32_t k = 0; k < entry.length; ++k) out.push_back(out[entry.offset + k]);
      entry.offset = start;
    } else if (c == dictionary.size()) {
      // The code being defined right now: w followed by w's first character.
      const std::uint32_t start = std::uint32_t(out.size());
      for (std::uint32_t k = 0; k < w.length; ++k) out.push_back(out[w.offset + k]);
      out.push_back(out[w.offset]);
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
