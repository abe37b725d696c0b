#include "core/render/image.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include <zlib.h>

#include "core/util/output_file.h"

namespace handlab::render {
namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

void put_chunk(std::vector<std::uint8_t>& out, const char type[4],
               const std::vector<std::uint8_t>& data) {
  put_u32(out, std::uint32_t(data.size()));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  const uLong crc = crc32(0L, out.data() + type_at, uInt(4 + data.size()));
  put_u32(out, std::uint32_t(crc));
}

}  // namespace

std::array<std::uint8_t, 4> Image::pixel(int x, int y) const {
  const std::size_t at = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
  return {rgba[at], rgba[at + 1], rgba[at + 2], rgba[at + 3]};
}

void write_png(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4)
    throw std::runtime_error("write_png: image has no pixels or the wrong size");

  // Scanlines with filter type 0 (none), then one zlib stream.
  const std::size_t row = std::size_t(image.width) * 4;
  std::vector<std::uint8_t> raw;
  raw.reserve((row + 1) * std::size_t(image.height));
  for (int y = 0; y < image.height; ++y) {
    raw.push_back(0);
    const auto* begin = image.rgba.data() + std::size_t(y) * row;
    raw.insert(raw.end(), begin, begin + row);
  }
  uLongf packed_size = compressBound(uLong(raw.size()));
  std::vector<std::uint8_t> packed(packed_size);
  if (compress2(packed.data(), &packed_size, raw.data(), uLong(raw.size()), 6) != Z_OK)
    throw std::runtime_error("write_png: zlib compression failed");
  packed.resize(packed_size);

  std::vector<std::uint8_t> ihdr;
  put_u32(ihdr, std::uint32_t(image.width));
  put_u32(ihdr, std::uint32_t(image.height));
  ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0});  // 8 bits, RGBA, deflate, no filter set, no interlace

  std::vector<std::uint8_t> file = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  put_chunk(file, "IHDR", ihdr);
  put_chunk(file, "IDAT", packed);
  put_chunk(file, "IEND", {});

  util::write_output_bytes(
      path, std::string_view(reinterpret_cast<const char*>(file.data()), file.size()));
}

bool read_png_size(const std::string& path, int* width, int* height) {
  std::ifstream in(path, std::ios::binary);
  std::uint8_t head[24] = {};
  if (!in.read(reinterpret_cast<char*>(head), sizeof head)) return false;
  static const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (std::memcmp(head, signature, 8) != 0 || std::memcmp(head + 12, "IHDR", 4) != 0) return false;
  auto u32 = [&](int at) {
    return int(head[at]) << 24 | int(head[at + 1]) << 16 | int(head[at + 2]) << 8 |
           int(head[at + 3]);
  };
  *width = u32(16);
  *height = u32(20);
  return true;
}

}  // namespace handlab::render
