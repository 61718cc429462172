#pragma once
// One BMP slice of a micro-CT stack (SkyScan's reconstruction writes 8-bit
// BMPs by default), decoded whole by SDL2's BMP reader — palettes, RLE, top-down
// rows and the V4/V5 headers other tools write — after MillSim has read the
// header's size itself, so a hostile header cannot make it allocate for more
// than 2^28 pixels. Internal to libmillsim_medical (SliceStack.cpp).
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace millsim::medical {

class BmpSlice {
public:
  // Reads and checks the file: one grey value a pixel (a palette or colour
  // pixels whose red, green and blue are equal); a VolumeError otherwise.
  explicit BmpSlice(const std::filesystem::path& file);
  // The size its header says (checked: 1 to 65536 a side, at most 2^28
  // pixels), without decoding it; a VolumeError otherwise.
  static glm::ivec2 headerSize(const std::filesystem::path& file);

  glm::ivec2 size() const { return size_; }
  // Row y (0 at the top, as TIFF and PNG slices are read), size().x grey values.
  const unsigned char* row(int y) const { return grey_.data() + std::size_t(y) * std::size_t(size_.x); }

private:
  glm::ivec2 size_{0};
  std::vector<unsigned char> grey_;
};

}  // namespace millsim::medical
