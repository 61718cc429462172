#include "millsim/volume/BmpSlice.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <SDL_error.h>
#include <SDL_pixels.h>
#include <SDL_rwops.h>
#include <SDL_surface.h>

#include "millsim/volume/VolumeError.h"

namespace millsim::medical {

namespace {

constexpr long kMaxSide = 1L << 16;
// A slice is decoded whole (SDL2 has no row API), so its pixels are capped:
// 2^28 is a 16384² slice, 1 GiB as SDL's 32-bit surface at worst.
constexpr long kMaxPixels = 1L << 28;

std::uint32_t le(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

}  // namespace

// Read before SDL allocates for it.
glm::ivec2 BmpSlice::headerSize(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) throw VolumeError(name + ": cannot open it");
  unsigned char h[26] = {};
  const std::size_t got = std::fread(h, 1, sizeof h, f.get());
  if (got < 2 || h[0] != 'B' || h[1] != 'M') throw VolumeError(name + ": not a BMP file (it does not start with \"BM\")");
  if (got < sizeof h) throw VolumeError(name + ": its BMP header is cut short (" + std::to_string(got) + " bytes)");
  const std::uint32_t infoSize = le(h + 14, 4);
  long w, hgt;
  if (infoSize == 12) {  // OS/2's core header: 16-bit sizes
    w = long(le(h + 18, 2)), hgt = long(le(h + 20, 2));
  } else {
    w = long(std::int32_t(le(h + 18, 4))), hgt = std::labs(long(std::int32_t(le(h + 22, 4))));  // negative: top-down
  }
  if (w < 1 || hgt < 1 || w > kMaxSide || hgt > kMaxSide)
    throw VolumeError(name + " is " + std::to_string(w) + " × " + std::to_string(hgt) +
                      " pixels; expected 1 to 65536 a side");
  if (w * hgt > kMaxPixels)
    throw VolumeError(name + " is " + std::to_string(w) + " × " + std::to_string(hgt) + " pixels; a BMP slice is read whole, "
                      "so it may have at most " + std::to_string(kMaxPixels) + " pixels: save the stack as TIFF or PNG");
  return {int(w), int(hgt)};
}

BmpSlice::BmpSlice(const std::filesystem::path& file) {
  const std::string name = file.string();
  size_ = headerSize(file);
  std::unique_ptr<SDL_Surface, void (*)(SDL_Surface*)> s(SDL_LoadBMP_RW(SDL_RWFromFile(file.c_str(), "rb"), 1),
                                                         &SDL_FreeSurface);
  if (!s) {
    const std::string why = SDL_GetError();
    // SDL says "Error reading from datastream" for a file that ends early.
    throw VolumeError(name + ": not a BMP SDL2 can read (" + why + ")" +
                      (why.find("reading") != std::string::npos ? "; is the file cut short?" : ""));
  }
  if (s->w != size_.x || s->h != size_.y)
    throw VolumeError(name + ": SDL2 read " + std::to_string(s->w) + " × " + std::to_string(s->h) +
                      " pixels where the header says " + std::to_string(size_.x) + " × " + std::to_string(size_.y));
  const SDL_PixelFormat* f = s->format;
  const SDL_Palette* palette = f->palette;
  const int bytes = f->BytesPerPixel;
  if (!palette && bytes < 2)
    throw VolumeError(name + ": " + std::to_string(f->BitsPerPixel) + "-bit pixels without a palette");
  grey_.resize(std::size_t(size_.x) * std::size_t(size_.y));
  if (SDL_MUSTLOCK(s.get())) SDL_LockSurface(s.get());
  for (int y = 0; y < size_.y; ++y) {
    const auto* in = static_cast<const unsigned char*>(s->pixels) + std::size_t(y) * std::size_t(s->pitch);
    unsigned char* out = grey_.data() + std::size_t(y) * std::size_t(size_.x);
    for (int x = 0; x < size_.x; ++x) {
      SDL_Color c;
      if (palette) {
        const int index = in[x];  // SDL unpacks 1- and 4-bit pixels to a byte each
        if (index >= palette->ncolors)
          throw VolumeError(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is colour " +
                            std::to_string(index) + " of a palette of " + std::to_string(palette->ncolors));
        c = palette->colors[index];
      } else {
        std::uint32_t v = 0;
        std::memcpy(&v, in + std::size_t(x) * std::size_t(bytes), std::size_t(bytes) > 4 ? 4 : std::size_t(bytes));
        SDL_GetRGB(v, f, &c.r, &c.g, &c.b);
      }
      if (c.r != c.g || c.g != c.b)
        throw VolumeError(name + " is not greyscale: pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is (" +
                          std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) +
                          "); a slice is one grey channel");
      out[x] = c.r;
    }
  }
  if (SDL_MUSTLOCK(s.get())) SDL_UnlockSurface(s.get());
}

}  // namespace millsim::medical
