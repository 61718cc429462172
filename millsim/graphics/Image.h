#pragma once
// An 8-bit RGBA picture, rows from the top (as PNG stores them, not as
// OpenGL reads them). Header-only.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace millsim {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width · height · 4 bytes

  glm::u8vec4 at(int x, int y) const {
    const std::uint8_t* p = rgba.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
    return {p[0], p[1], p[2], p[3]};
  }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
};

// Turns `rows` rows of `rowBytes` bytes upside down in place (OpenGL's rows
// run from the bottom, PNG's and JPEG's from the top).
inline void flipRows(std::uint8_t* data, std::size_t rowBytes, int rows) {
  for (int y = 0; y < rows / 2; ++y)
    std::swap_ranges(data + std::size_t(y) * rowBytes, data + std::size_t(y + 1) * rowBytes,
                     data + std::size_t(rows - 1 - y) * rowBytes);
}

}  // namespace millsim
