#pragma once
// The heads-up display and the cut-plane panel of the window (Dear ImGui).
// Internal to libmillsim_window; call between ImGui::NewFrame and ImGui::Render.
#include <string>
#include <vector>

#include "millsim/graphics/SceneView.h"
#include "millsim/window/AppWindow.h"

namespace millsim {

struct HudExtras {
  std::vector<std::string> renderers;  // for keys 1, 2, 3 …
  std::string viewName;                // the viewpoint looked through, or "framed"
  double windowMs = 0.0;               // the window's own frame time
  bool pointer = false;                // a MouseDevice
};

void drawHud(const HudState& hud, const HudExtras& extras);
// The keys, wrapped along the bottom of the window.
void drawHelpLine(const HudExtras& extras);
// Sliders for each cut plane, and whether cuts are capped by their section;
// returns true if the user changed one.
bool drawCutPanel(std::vector<CutPlane>& planes, int& active, const glm::dvec3& centre, double size, bool& capped);

}  // namespace millsim
