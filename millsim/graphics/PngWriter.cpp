// writePng (SceneRenderer.h): libpng's simplified write API.
#include <cerrno>
#include <cstring>
#include <png.h>

#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/SceneRenderer.h"

namespace millsim {

void writePng(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4)
    throw GraphicsError(path.string() + ": cannot write an empty or malformed " + std::to_string(image.width) + "x" +
                        std::to_string(image.height) + " image");
  // Opened here rather than by libpng so that the message can say why.
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw GraphicsError(path.string() + ": cannot write the PNG file (" + std::strerror(errno) + ")");
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGBA;
  const int ok = png_image_write_to_stdio(&png, f, 0, image.rgba.data(), 0, nullptr);
  const std::string why = ok ? "" : png.message;
  png_image_free(&png);
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed)
    throw GraphicsError(path.string() + ": writing the PNG failed (" + (ok ? std::strerror(errno) : why) + ")");
}

}  // namespace millsim
