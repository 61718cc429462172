#pragma once
#include "millsim/std/ShapeKinds.h"

namespace millsim {

// A PNG or JPEG image wrapped on a Shape's geometry (its colours replace the
// Material's diffuseColor; a grey image modulates it). The url is resolved
// like an Inline's (relative to the scene file, local files only).
class ImageTexture : public TextureNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InputOutput, {}, "The image file, tried in order (PNG or JPEG)."};
  SFBool repeatS{this, "repeatS", Access::InitializeOnly, true, "Whether the image repeats along s (else its edge is stretched)."};
  SFBool repeatT{this, "repeatT", Access::InitializeOnly, true, "Whether the image repeats along t (else its edge is stretched)."};
  SFString description{this, "description", Access::InputOutput, "", "What the image shows."};
  SFBool load{this, "load", Access::InputOutput, true, "Whether to load the image. MillSim reads it when drawing starts."};
  SFTime autoRefresh{this, "autoRefresh", Access::InputOutput, Time{0}, "Reload interval (s). Accepted; not acted on by MillSim.",
                     Range::closed(0, 1e9)};
  SFTime autoRefreshTimeLimit{this, "autoRefreshTimeLimit", Access::InputOutput, Time{3600},
                              "How long to keep reloading (s). Accepted; not acted on by MillSim.", Range::closed(0, 1e9)};

  // Finds the first url that is a local PNG or JPEG file; warns when none is.
  void initialize(DiagnosticSink& sink) override;
  // The image file found at load (absolute), or empty: drawn without texture.
  const std::string& imageFile() const { return imageFile_; }

private:
  std::string imageFile_;
};

}  // namespace millsim
