#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// How a Text is set: font family and style, size, line spacing, justification.
// MillSim draws with the DejaVu fonts (found through fontconfig): SERIF,
// SANS and TYPEWRITER map to DejaVu Serif, Sans and Sans Mono.
class FontStyle : public FontStyleNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString family{this, "family", Access::InputOutput, {"SERIF"},
                  "Font families in order of preference: SERIF, SANS, TYPEWRITER or a fontconfig family name."};
  SFString style{this, "style", Access::InputOutput, "PLAIN", "PLAIN, BOLD, ITALIC or BOLDITALIC."};
  SFFloat size{this, "size", Access::InputOutput, 1.f, "Nominal height of a line of text (m).",
               Range::openClosed(0, 1e4).in(quantity::length)};
  SFFloat spacing{this, "spacing", Access::InputOutput, 1.f, "Distance between lines, in multiples of size.", Range::closed(0, 1e3)};
  MFString justify{this, "justify", Access::InputOutput, {"BEGIN"},
                   "Major then minor alignment: BEGIN, FIRST, MIDDLE or END (FIRST: the first line's baseline at y = 0)."};
  SFBool horizontal{this, "horizontal", Access::InputOutput, true,
                    "Whether lines run horizontally. MillSim sets horizontal text only; false is accepted and drawn horizontally."};
  SFBool leftToRight{this, "leftToRight", Access::InputOutput, true,
                     "Whether characters run left to right. Accepted; MillSim sets left to right."};
  SFBool topToBottom{this, "topToBottom", Access::InputOutput, true, "Whether lines follow each other downwards (false: upwards)."};
  SFString language{this, "language", Access::InputOutput, "", "The text's language (RFC 3066). Accepted; not acted on by MillSim."};

  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
