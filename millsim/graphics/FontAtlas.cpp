#include "millsim/graphics/FontAtlas.h"

#include <algorithm>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include "millsim/graphics/GraphicsError.h"

namespace millsim {

namespace {

constexpr int kAtlasSize = 1024;
// Glyphs are rasterised this many pixels to the em: sharp at the sizes a label
// takes on screen, and about 200 of them fit one atlas.
constexpr int kPixelsPerEm = 56;

// The font file fontconfig picks for an X3D family and style.
std::string findFont(const std::string& family, const std::string& style) {
  const std::string name = family == "SERIF" ? "DejaVu Serif" : family == "SANS" ? "DejaVu Sans"
                           : family == "TYPEWRITER"                                 ? "DejaVu Sans Mono"
                                                                                    : family;
  FcConfig* config = FcInitLoadConfigAndFonts();
  if (!config) throw GraphicsError("fontconfig could not load its configuration");
  FcPattern* pattern = FcPatternCreate();
  FcPatternAddString(pattern, FC_FAMILY, reinterpret_cast<const FcChar8*>(name.c_str()));
  FcPatternAddInteger(pattern, FC_WEIGHT, style.find("BOLD") != std::string::npos ? FC_WEIGHT_BOLD : FC_WEIGHT_REGULAR);
  FcPatternAddInteger(pattern, FC_SLANT, style.find("ITALIC") != std::string::npos ? FC_SLANT_ITALIC : FC_SLANT_ROMAN);
  FcConfigSubstitute(config, pattern, FcMatchPattern);
  FcDefaultSubstitute(pattern);
  FcResult result = FcResultNoMatch;
  FcPattern* match = FcFontMatch(config, pattern, &result);
  std::string file;
  FcChar8* path = nullptr;
  if (match && FcPatternGetString(match, FC_FILE, 0, &path) == FcResultMatch) file = reinterpret_cast<const char*>(path);
  if (match) FcPatternDestroy(match);
  FcPatternDestroy(pattern);
  FcConfigDestroy(config);
  if (file.empty())
    throw GraphicsError("no font found for FontStyle family '" + family + "' (install fonts-dejavu-core)");
  return file;
}

}  // namespace

struct FontAtlas::Face {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~Face() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
};

FontAtlas::FontAtlas(const std::string& family, const std::string& style)
    : face_(std::make_unique<Face>()), file_(findFont(family, style)), pixels_(std::size_t(kAtlasSize) * kAtlasSize, 0) {
  if (FT_Init_FreeType(&face_->library)) throw GraphicsError("FreeType does not initialise");
  if (FT_New_Face(face_->library, file_.c_str(), 0, &face_->face))
    throw GraphicsError("FreeType cannot read the font '" + file_ + "'");
  FT_Set_Pixel_Sizes(face_->face, 0, kPixelsPerEm);
  const FT_Size_Metrics& m = face_->face->size->metrics;
  ascent_ = float(m.ascender) / 64.f / kPixelsPerEm;
  descent_ = -float(m.descender) / 64.f / kPixelsPerEm;
}

FontAtlas::~FontAtlas() {
  if (texture_) glDeleteTextures(1, &texture_);
}

const Glyph& FontAtlas::glyph(char32_t codepoint) {
  if (auto it = glyphs_.find(codepoint); it != glyphs_.end()) return it->second;
  Glyph g;
  FT_Face f = face_->face;
  if (FT_Load_Char(f, FT_ULong(codepoint), FT_LOAD_RENDER) == 0) {
    const FT_Bitmap& b = f->glyph->bitmap;
    g.advance = float(f->glyph->advance.x) / 64.f / kPixelsPerEm;
    const int w = int(b.width), h = int(b.rows);
    if (w > 0 && h > 0) {
      if (penX_ + w + 1 > kAtlasSize) penX_ = 1, penY_ += rowHeight_ + 1, rowHeight_ = 0;
      if (penY_ + h + 1 <= kAtlasSize) {
        // FreeType's rows run top-down; the atlas's bottom-up (GL's texture origin).
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            pixels_[std::size_t(penY_ + h - 1 - y) * kAtlasSize + std::size_t(penX_ + x)] =
                b.buffer[std::size_t(y) * std::size_t(std::abs(b.pitch)) + std::size_t(x)];
        g.offset = glm::vec2(float(f->glyph->bitmap_left), float(f->glyph->bitmap_top - h)) / float(kPixelsPerEm);
        g.size = glm::vec2(float(w), float(h)) / float(kPixelsPerEm);
        g.uvMin = glm::vec2(float(penX_), float(penY_)) / float(kAtlasSize);
        g.uvMax = glm::vec2(float(penX_ + w), float(penY_ + h)) / float(kAtlasSize);
        g.drawn = true;
        penX_ += w + 1;
        rowHeight_ = std::max(rowHeight_, h);
        dirty_ = true;
      }
    }
  }
  return glyphs_.emplace(codepoint, g).first->second;
}

void FontAtlas::bind() {
  if (!texture_) {
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  if (dirty_) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, kAtlasSize, kAtlasSize, 0, GL_RED, GL_UNSIGNED_BYTE, pixels_.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    dirty_ = false;
  }
}

}  // namespace millsim
