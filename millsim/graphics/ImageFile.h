#pragma once
// Reading an ImageTexture's file: PNG (libpng) or JPEG (libjpeg-turbo), as
// 8-bit RGBA with rows from the bottom (OpenGL's texture origin, so that
// t = 0 is the image's bottom edge as X3D wants). Internal to the graphics library.
#include <cstdint>
#include <string>
#include <vector>

namespace millsim {

struct TextureImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  bool grey = false;  // one or two channels: X3D modulates the material colour by it
};

// Throws GraphicsError naming the file and what is wrong with it.
TextureImage readTextureImage(const std::string& path);

}  // namespace millsim
