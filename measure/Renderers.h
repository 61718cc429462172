#pragma once
// Renderers by registry name, configured by field name — so every suite works
// on any HapticsRendererNode, including ones that land later (BarbicRenderer)
// or come from plugins, without code changes here.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "millsim/haptics/HapticsRenderer.h"

namespace millsim::measure {

using FieldValues = std::vector<std::pair<std::string, std::string>>;  // field name, X3D value text

struct RendererSpec {
  std::string type;      // registry name, e.g. "LineProxyRenderer"
  FieldValues fields;    // overrides of the node's defaults
  std::string label() const;  // "LineProxyRenderer vertexCount=51"
};

// The renderer types registered in the builtin registry, in name order.
std::vector<std::string> registeredRenderers();
bool isRegistered(const std::string& type);

// A node of `spec.type` with its fields set; throws std::runtime_error naming
// the unknown type or field, or the value the field refused.
std::shared_ptr<HapticsRendererNode> makeRenderer(const RendererSpec& spec);

// What a renderer type declares about itself (millsim/haptics/RendererTraits.h):
// makeRenderer({type, {}})->traits(). Throws like makeRenderer for unknown types.
RendererTraits rendererTraits(const std::string& type);

// The tool every suite uses: a 1 mm round burr on a 0.5 mm shaft.
ToolGeometry standardTool();

// Height of the burr centre above a flat surface at which the renderer first
// reports a force (0 for a centre-point proxy, about the burr radius for
// surface points), found by a slow kinematic descent onto a half-space. The
// suites press "the part each renderer feels" by this offset.
double contactOffset(const HapticsRendererNode& renderer, const ToolGeometry& tool, double h);

// The stiffness the device meets on a flat surface voxelised at h (N/m): the
// force difference between two quasi-static depths past first contact (0.2h
// and 0.6h) over their distance, so an error in the contact height cancels.
// #1: its proxy spring; #2: its springConstant shared among the touching
// points; #3: the coupling in series with the contact. `depth1`, `depth2` (m,
// past first contact) replace 0.2h and 0.6h when positive: the physical suite
// takes the slope at the same depths at every h.
double renderedStiffness(const HapticsRendererNode& renderer, const ToolGeometry& tool, double h,
                         double depth1 = 0.0, double depth2 = 0.0);

}  // namespace millsim::measure
