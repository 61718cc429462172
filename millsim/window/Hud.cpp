#include "millsim/window/Hud.h"

#include <cmath>
#include <numbers>

#include <imgui.h>

namespace millsim {

void drawHud(const HudState& hud, const HudExtras& extras) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.55f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("HUD", nullptr, flags)) {
    ImGui::Text("%s%s", hud.renderer.c_str(), hud.swapPending ? "  (swap pending)" : "");
    if (!hud.burr.empty()) ImGui::Text("burr: %s", hud.burr.c_str());
    ImGui::Text("haptic rate  %7.0f Hz", hud.hapticRate);
    ImGui::Text("compute      %5.0f µs p50  %5.0f µs p99", hud.computeP50Us, hud.computeP99Us);
    ImGui::Text("force        %7.3f N    torque %7.4f N·m%s", hud.force, hud.torque,
                hud.torqueNotOutput ? " (not output)" : "");
    ImGui::Text("contacts     %7d      removed %8.3f mm³", hud.contacts, hud.removedMm3);
    ImGui::Text("milling      %s", hud.milling ? "ON" : "off");
    ImGui::Text("view         %s   (window %4.1f ms)", extras.viewName.c_str(), extras.windowMs);
    if (!hud.status.empty()) ImGui::TextColored(ImVec4(1.f, 0.85f, 0.3f, 1.f), "%s", hud.status.c_str());
  }
  ImGui::End();
}

void drawHelpLine(const HudExtras& extras) {
  std::string keys;
  for (std::size_t i = 0; i < extras.renderers.size(); ++i)
    keys += std::to_string(i + 1) + " " + extras.renderers[i] + "   ";
  // The view's drags differ when the mouse is the tool (SdlWindow.cpp, motion()).
  const char* view = extras.pointer ? "Alt+drag or middle-drag turn view · Shift+middle-drag pan · wheel zoom · "
                                    : "drag turn · Shift+drag or middle-drag pan · wheel zoom · ";
  std::string help = keys + "|  " + view +
                     "PgUp/PgDn viewpoint · F frame all · C cut · F1-F6 toggle cut · Tab next cut · Ctrl+drag move "
                     "cut · K cut caps · E force on/off · M millable on/off · B burr shape · H HUD · Esc quit";
  if (extras.pointer)
    help += "  |  mouse tool: move = burr · left/Space = mill · right-drag turn tool · Ctrl+wheel depth";
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.f, size.y), ImGuiCond_Always, ImVec2(0.f, 1.f));
  ImGui::SetNextWindowSize(ImVec2(size.x, 0.f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.45f);
  if (ImGui::Begin("Keys", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs |
                                        ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing)) {
    ImGui::PushTextWrapPos(0.f);
    ImGui::TextDisabled("%s", help.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
}

bool drawCutPanel(std::vector<CutPlane>& planes, int& active, const glm::dvec3& centre, double size, bool& capped) {
  if (planes.empty()) return false;
  bool changed = false;
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 10, 10), ImGuiCond_Always, ImVec2(1.f, 0.f));
  ImGui::SetNextWindowBgAlpha(0.55f);
  if (ImGui::Begin("Cut planes", nullptr,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove)) {
    changed |= ImGui::Checkbox("capped by tissue (K)", &capped);
    for (std::size_t i = 0; i < planes.size(); ++i) {
      CutPlane& c = planes[i];
      ImGui::PushID(int(i));
      changed |= ImGui::Checkbox("##on", &c.enabled);
      ImGui::SameLine();
      if (ImGui::RadioButton(c.name.c_str(), active == int(i))) active = int(i);
      if (active == int(i)) {
        // Offset from the scene centre along the normal, and the normal's two angles.
        glm::dvec3 n(c.plane);
        float offset = float((glm::dot(n, centre) + c.plane.w) * 1e3);  // mm
        float azimuth = float(std::atan2(n.x, n.z) * 180.0 / std::numbers::pi);
        float elevation = float(std::asin(std::clamp(n.y, -1.0, 1.0)) * 180.0 / std::numbers::pi);
        const float half = float(size * 1e3);
        bool moved = ImGui::SliderFloat("offset (mm)", &offset, -half, half, "%.2f");
        moved |= ImGui::SliderFloat("azimuth (°)", &azimuth, -180.f, 180.f, "%.0f");
        moved |= ImGui::SliderFloat("elevation (°)", &elevation, -90.f, 90.f, "%.0f");
        if (moved) {
          const double az = azimuth * std::numbers::pi / 180.0, el = elevation * std::numbers::pi / 180.0;
          n = glm::dvec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
          c.plane = glm::dvec4(n, double(offset) * 1e-3 - glm::dot(n, centre));
          changed = true;
        }
      }
      ImGui::PopID();
    }
  }
  ImGui::End();
  return changed;
}

}  // namespace millsim
