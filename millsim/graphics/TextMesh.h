#pragma once
// Setting a Text (X3D 4.0, 15): its lines as textured quads in the local XY
// plane, one per glyph, with FontStyle's size, spacing and justification and
// Text's length and maxExtent. UTF-8 in; glyphs the font lacks draw nothing.
#include <string>

#include "millsim/graphics/SceneView.h"
#include "millsim/graphics/TriangleMesh.h"

namespace millsim {

class FontAtlas;

TriangleMesh layoutText(const DrawText& text, FontAtlas& font);

// Code points of UTF-8 text; a malformed byte reads as U+FFFD.
std::u32string decodeUtf8(const std::string& text);

}  // namespace millsim
