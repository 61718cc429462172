#include "ImageCompare.h"

#include <png.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace millsim::test {

Image readPng(const std::filesystem::path& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw std::runtime_error(path.string() + ": cannot read the PNG (" + png.message + ")");
  png.format = PNG_FORMAT_RGBA;
  Image img;
  img.width = int(png.width);
  img.height = int(png.height);
  img.rgba.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, img.rgba.data(), 0, nullptr)) {
    const std::string why = png.message;
    png_image_free(&png);
    throw std::runtime_error(path.string() + ": cannot decode the PNG (" + why + ")");
  }
  return img;
}

ImageDifference compareImages(const Image& a, const Image& b, Image* diff) {
  ImageDifference d;
  d.total = std::size_t(a.width) * std::size_t(a.height);
  if (a.width != b.width || a.height != b.height) {
    d.differing = d.total;
    d.maxChannel = 255;
    return d;
  }
  if (diff) *diff = a;
  for (std::size_t p = 0; p < d.total; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.rgba[4 * p + c]) - int(b.rgba[4 * p + c])));
    d.maxChannel = std::max(d.maxChannel, worst);
    const bool differs = worst > kChannelTolerance;
    d.differing += differs;
    if (diff)
      for (int c = 0; c < 3; ++c)
        diff->rgba[4 * p + c] = differs ? (c == 0 ? 255 : 0) : std::uint8_t(a.rgba[4 * p + c] / 3);
  }
  return d;
}

bool updatingReferences() {
  const char* v = std::getenv("MILLSIM_UPDATE_REFERENCES");
  return v && *v && std::string(v) != "0";
}

}  // namespace millsim::test
