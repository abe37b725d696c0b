// An 8-bit RGBA picture, rows top to bottom, and PNG output.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace handlab::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4, row 0 at the top

  std::array<std::uint8_t, 4> pixel(int x, int y) const;
};

// Writes an 8-bit RGBA PNG (zlib-compressed); throws std::runtime_error on I/O failure.
void write_png(const Image& image, const std::string& path);

// Reads width and height from a PNG file's header; false if the file is not a PNG.
bool read_png_size(const std::string& path, int* width, int* height);

}  // namespace handlab::render
