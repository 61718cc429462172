#pragma once
// FontAtlas: one font face (found by fontconfig, rasterised by FreeType) and
// the glyphs drawn so far, packed into one single-channel OpenGL texture that
// Text is drawn from. Glyphs are added as text first needs them. Internal to
// the graphics library; needs the GL context current.
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>

namespace millsim {

struct Glyph {
  glm::vec2 offset{0.f};    // bitmap's lower-left corner from the pen on the baseline (em)
  glm::vec2 size{0.f};      // bitmap size (em)
  glm::vec2 uvMin{0.f}, uvMax{0.f};
  float advance = 0.f;      // em
  bool drawn = false;       // false: blank (a space) or did not fit the atlas
};

class FontAtlas {
public:
  // X3D's family (SERIF, SANS, TYPEWRITER or a fontconfig name) and style
  // (PLAIN, BOLD, ITALIC, BOLDITALIC). Throws GraphicsError when no font is found.
  FontAtlas(const std::string& family, const std::string& style);
  ~FontAtlas();
  FontAtlas(const FontAtlas&) = delete;
  FontAtlas& operator=(const FontAtlas&) = delete;

  const Glyph& glyph(char32_t codepoint);
  float ascent() const { return ascent_; }    // em
  float descent() const { return descent_; }  // em, positive below the baseline
  const std::string& file() const { return file_; }
  // Binds the texture to unit 0, first uploading glyphs added since the last bind.
  void bind();

private:
  struct Face;
  std::unique_ptr<Face> face_;
  std::string file_;
  float ascent_ = 0.8f, descent_ = 0.2f;
  std::unordered_map<char32_t, Glyph> glyphs_;
  std::vector<std::uint8_t> pixels_;  // the atlas, kSize × kSize, rows from the bottom
  int penX_ = 1, penY_ = 1, rowHeight_ = 0;
  bool dirty_ = true;
  unsigned texture_ = 0;
};

}  // namespace millsim
