#pragma once
// RendererPool: every haptics renderer type a scene can use, compiled once on
// the scene thread before a live run, so that a swap while running (keys 1, 2,
// 3 in the window, or a new node in the device's hapticsRenderer field) hands
// a ready algorithm to HapticLoop::replaceRenderer: nothing is built on the
// haptic thread, and Barbic's point shells exist before it takes over (the
// VoxelScene keeps every shell current with milling).
//
// Slots: LineProxyRenderer, SurfacePointRenderer, BarbicRenderer (keys 1, 2,
// 3), then any other registered renderer type (plugins) by name. The device's
// own renderer node serves its type's slot, so its authored fields hold; the
// other types run with their defaults. A type that cannot render the burr
// (LineProxyRenderer and a non-round head) stays in its slot, refusing with
// its reason when selected.
//
// A burr swap (the device's MillTool fields changed: the B key, a route, a
// plugin) compiles the rendering algorithm again for the new burr and hands it
// over with the burr (HapticLoop::replaceRenderer), cross-faded like any swap;
// the other slots are compiled again for it. Scene thread only.
#include <memory>
#include <string>
#include <vector>

#include "millsim/core/FieldWatch.h"
#include "millsim/haptics/HapticsRenderer.h"

namespace millsim {

class HapticLoop;
class HapticsRendererNode;
class Node;
class Scene;
struct CompiledRun;

class RendererPool {
public:
  // `initial`: the algorithm the loop starts with (compiled from the device's
  // renderer node; the pool only remembers it). Throws std::runtime_error if
  // one of the other types cannot be compiled for this scene.
  RendererPool(Scene& scene, CompiledRun& run, const HapticAlgorithm* initial);
  ~RendererPool();

  std::size_t size() const { return slots_.size(); }
  const std::string& typeName(std::size_t slot) const { return slots_[slot].type; }
  std::vector<std::string> typeNames() const;
  std::size_t current() const { return current_; }

  // Hands slot `slot`'s algorithm to the loop and sets the device's
  // hapticsRenderer field to its node. Returns what to tell the user.
  std::string select(std::size_t slot, HapticLoop& loop);
  // Takes algorithms the loop retired back into their slots.
  void collect(HapticLoop& loop);
  // A prepared renderer node's fields changed (a route, a plugin): a renderer
  // whose traits say compilesWithoutScene is compiled again here and swapped
  // in (cross-faded) if it is rendering; for others the change waits for the
  // next run. Returns what to tell the user (empty: nothing changed).
  std::string followRendererFields(HapticLoop& loop);
  // The device's hapticsRenderer field was set (by a route or a plugin): swap
  // to that node's slot. Returns what to tell the user (empty: nothing changed).
  std::string followDeviceField(HapticLoop& loop);
  // The device's MillTool changed (the B key, a route, a plugin): swap to the
  // new burr, or refuse it — setting the fields back to the burr that stays —
  // if it is not a valid burr or the rendering type cannot render it.
  // Returns what to tell the user (empty: nothing changed).
  std::string followTool(HapticLoop& loop);
  // The burr every slot is compiled for (the one milling, once a pending swap lands).
  const ToolGeometry& tool() const;

private:
  struct Slot {
    std::string type;
    std::shared_ptr<Node> node;                  // the renderer node (the device's, or a default one)
    std::unique_ptr<HapticAlgorithm> algorithm;  // null while the loop has it
    const HapticAlgorithm* identity = nullptr;   // recognises it when it comes back
    FieldWatch fields;                           // the node's fields: changed since last compiled?
    ToolGeometry tool;                           // the burr `algorithm` was compiled for
    std::string refusal;                         // why this type cannot render that burr (empty: it can)
  };
  // Compiles the slot's node for run_.tool (its algorithm must be here).
  void prepare(Slot& s);
  CompiledRun& run_;
  std::vector<Slot> slots_;
  std::size_t current_ = 0;
  const Node* fieldSeen_ = nullptr;  // the hapticsRenderer value last acted on
};

}  // namespace millsim
