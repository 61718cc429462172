#include "millsim/graphics/ImageFile.h"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include <jpeglib.h>
#include <png.h>

#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/Image.h"

namespace millsim {

namespace {

// Larger images are refused rather than allocated: a texture beyond GL's
// guaranteed size would not draw anyway.
constexpr int kMaxSide = 8192;

void checkSize(const std::string& path, long width, long height) {
  if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide)
    throw GraphicsError(path + ": image of " + std::to_string(width) + "x" + std::to_string(height) +
                        " pixels; expected 1 to " + std::to_string(kMaxSide) + " on each side");
}

TextureImage readPng(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw GraphicsError(path + ": not a readable PNG file (" + png.message + ")");
  TextureImage img;
  img.grey = (png.format & PNG_FORMAT_FLAG_COLOR) == 0;
  try {
    checkSize(path, long(png.width), long(png.height));
  } catch (...) {
    png_image_free(&png);
    throw;
  }
  img.width = int(png.width), img.height = int(png.height);
  png.format = PNG_FORMAT_RGBA;
  img.rgba.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, img.rgba.data(), 0, nullptr))
    throw GraphicsError(path + ": the PNG data is damaged (" + png.message + ")");
  flipRows(img.rgba.data(), std::size_t(img.width) * 4, img.height);
  return img;
}

struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

TextureImage readJpeg(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw GraphicsError(path + ": cannot open the JPEG file");
  jpeg_decompress_struct info;
  JpegError error;
  info.err = jpeg_std_error(&error.manager);
  // libjpeg reports errors by calling error_exit, which must not return: jump back here.
  error.manager.error_exit = [](j_common_ptr c) {
    auto* e = reinterpret_cast<JpegError*>(c->err);
    (*c->err->format_message)(c, e->message);
    std::longjmp(e->jump, 1);
  };
  TextureImage img;
  std::vector<std::uint8_t> row;
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&info);
    throw GraphicsError(path + ": the JPEG data cannot be read (" + error.message + ")");
  }
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, file.get());
  jpeg_read_header(&info, TRUE);
  if (info.image_width > JDIMENSION(kMaxSide) || info.image_height > JDIMENSION(kMaxSide)) {
    const long w = long(info.image_width), h = long(info.image_height);
    jpeg_destroy_decompress(&info);
    checkSize(path, w, h);
  }
  info.out_color_space = info.jpeg_color_space == JCS_GRAYSCALE ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&info);
  img.width = int(info.output_width), img.height = int(info.output_height);
  img.grey = info.output_components == 1;
  img.rgba.resize(std::size_t(img.width) * std::size_t(img.height) * 4);
  row.resize(std::size_t(img.width) * std::size_t(info.output_components));
  while (info.output_scanline < info.output_height) {
    // Rows arrive top-down; stored bottom-up.
    std::uint8_t* out = img.rgba.data() + std::size_t(img.height - 1 - int(info.output_scanline)) * std::size_t(img.width) * 4;
    JSAMPROW rows[1] = {row.data()};
    jpeg_read_scanlines(&info, rows, 1);
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = row.data() + std::size_t(x) * std::size_t(info.output_components);
      out[x * 4 + 0] = p[0];
      out[x * 4 + 1] = img.grey ? p[0] : p[1];
      out[x * 4 + 2] = img.grey ? p[0] : p[2];
      out[x * 4 + 3] = 255;
    }
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return img;
}

}  // namespace

TextureImage readTextureImage(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw GraphicsError(path + ": cannot open the image file");
  unsigned char head[8] = {0};
  const std::size_t n = std::fread(head, 1, sizeof head, file.get());
  file.reset();
  if (n == 8 && std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0) return readPng(path);
  if (n >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) return readJpeg(path);
  throw GraphicsError(path + ": neither a PNG nor a JPEG file");
}

}  // namespace millsim
