#include "millsim/run/RendererPool.h"

#include <algorithm>
#include <stdexcept>

#include "millsim/core/FieldValues.h"
#include "millsim/core/Scene.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/run/RunSetup.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

namespace {
// The keys 1, 2, 3 of the window, in the paper's order (#1, #2, #3).
const char* const kKeyed[] = {"LineProxyRenderer", "SurfacePointRenderer", "BarbicRenderer"};
}  // namespace

RendererPool::RendererPool(Scene& scene, CompiledRun& run, const HapticAlgorithm* initial) : run_(run) {
  std::vector<std::string> types;
  for (const char* t : kKeyed)
    if (scene.registry.find(t)) types.push_back(t);
  for (const NodeType* t : scene.registry.all()) {
    if (std::find(types.begin(), types.end(), t->name) != types.end()) continue;
    if (dynamic_cast<HapticsRendererNode*>(t->create().get())) types.push_back(t->name);
  }
  const std::shared_ptr<HapticsRendererNode> own = run.device->hapticsRenderer.get();
  const std::string initialType = run.rendererName;
  for (const std::string& type : types) {
    Slot s;
    s.type = type;
    if (own && own->typeName() == type) {
      s.node = own;
    } else {
      s.node = scene.registry.create(type);
    }
    if (type == initialType) {
      s.identity = initial;
      s.tool = run.tool;
      current_ = slots_.size();
    } else {
      prepare(s);
    }
    s.fields = FieldWatch::ofNode(*s.node);
    slots_.push_back(std::move(s));
  }
  fieldSeen_ = own.get();
}

RendererPool::~RendererPool() = default;

const ToolGeometry& RendererPool::tool() const { return run_.tool; }

void RendererPool::prepare(Slot& s) {
  auto* node = dynamic_cast<HapticsRendererNode*>(s.node.get());
  s.tool = run_.tool;
  s.refusal.clear();
  try {
    s.algorithm = node->compile(run_.tool, *run_.scene);
  } catch (const std::exception& e) {
    // Kept, not fatal: the other renderers still swap, and this one says why not.
    s.algorithm.reset();
    s.refusal = e.what();
  }
  s.identity = s.algorithm.get();
}

std::vector<std::string> RendererPool::typeNames() const {
  std::vector<std::string> out;
  for (const Slot& s : slots_) out.push_back(s.type);
  return out;
}

std::string RendererPool::select(std::size_t slot, HapticLoop& loop) {
  if (slot >= slots_.size()) return "no renderer on that key";
  collect(loop);
  if (slot == current_) return slots_[slot].type + " is already rendering";
  Slot& s = slots_[slot];
  if (!s.refusal.empty()) return s.type + " cannot render this burr: " + s.refusal;
  if (!s.algorithm) return s.type + " is still fading out; try again";
  if (!loop.replaceRenderer(s.algorithm, &run_.tool)) return "a renderer swap is still pending; try again";
  current_ = slot;
  // The scene graph says what runs: the device's field follows the swap.
  auto node = std::dynamic_pointer_cast<HapticsRendererNode>(s.node);
  run_.device->hapticsRenderer.set(node);
  fieldSeen_ = node.get();
  run_.rendererName = s.type;
  return "switched to " + s.type;
}

void RendererPool::collect(HapticLoop& loop) {
  while (auto back = loop.takeRetired()) {
    auto it = std::find_if(slots_.begin(), slots_.end(), [&](const Slot& s) { return s.identity == back.get(); });
    if (it != slots_.end() && !it->algorithm) {
      it->algorithm = std::move(back);
      if (!(it->tool == run_.tool)) prepare(*it);  // it faded out during a burr swap: it needs the new burr
    }
    // An algorithm the pool does not know is freed here, on the scene thread.
  }
}

std::string RendererPool::followRendererFields(HapticLoop& loop) {
  std::string notice;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    Slot& s = slots_[i];
    if (!s.fields.changed()) continue;
    const auto& node = dynamic_cast<const HapticsRendererNode&>(*s.node);
    if (!node.traits().compilesWithoutScene) {
      s.fields.mark();
      notice = s.type + ": a field changed; it takes effect at the next run (its compile reads the scene)";
      continue;
    }
    std::unique_ptr<HapticAlgorithm> fresh;
    try {
      fresh = node.compile(run_.tool, *run_.scene);
    } catch (const std::exception& e) {
      s.fields.mark();
      notice = s.type + ": cannot apply the changed fields: " + e.what();
      continue;
    }
    s.refusal.clear();
    s.tool = run_.tool;
    if (i == current_) {
      const HapticAlgorithm* identity = fresh.get();
      if (!loop.replaceRenderer(fresh, &run_.tool)) continue;  // a swap is pending: try at the next tick
      s.identity = identity;  // the old one, when it retires, is freed by collect()
    } else {
      s.identity = fresh.get();
      s.algorithm = std::move(fresh);
    }
    s.fields.mark();
    notice = s.type + ": changed fields applied live";
  }
  return notice;
}

std::string RendererPool::followDeviceField(HapticLoop& loop) {
  const Node* now = run_.device->hapticsRenderer.get().get();
  if (now == fieldSeen_ || !now) return {};
  fieldSeen_ = now;
  for (std::size_t i = 0; i < slots_.size(); ++i)
    if (slots_[i].node.get() == now) return select(i, loop);
  return "hapticsRenderer was set to a new " + std::string(now->typeName()) +
         " node; a node other than the prepared ones takes effect at the next run";
}

std::string RendererPool::followTool(HapticLoop& loop) {
  MillTool* node = run_.device->tool.get().get();
  if (!node) return {};
  const ToolGeometry wanted = node->geometry();
  if (wanted == run_.tool) return {};
  // Refusing sets the fields back, so the scene graph says which burr mills.
  const ToolGeometry kept = run_.tool;
  auto restore = [&] { node->setGeometry(kept); };
  const std::string keptName = std::string(burrShapeName(kept.shape)) + " burr";
  if (std::string problem = node->problem(); !problem.empty()) {
    restore();
    return problem + "; the " + keptName + " stays";
  }
  Slot& current = slots_[current_];
  const auto& renderer = dynamic_cast<const HapticsRendererNode&>(*current.node);
  std::unique_ptr<HapticAlgorithm> fresh;
  try {
    fresh = renderer.compile(wanted, *run_.scene);
  } catch (const std::exception& e) {
    restore();
    return current.type + " cannot render a " + std::string(burrShapeName(wanted.shape)) + " burr (" + e.what() +
           "); the " + keptName + " stays";
  }
  const HapticAlgorithm* identity = fresh.get();
  if (!loop.replaceRenderer(fresh, &wanted)) return {};  // a swap is pending: try at the next tick
  run_.tool = wanted;
  current.identity = identity;  // the old one, when it retires, is freed by collect()
  current.tool = wanted;
  current.refusal.clear();
  // The others follow now (one still fading out follows when collect() takes it back).
  for (std::size_t i = 0; i < slots_.size(); ++i)
    if (i != current_ && (slots_[i].algorithm || !slots_[i].refusal.empty())) prepare(slots_[i]);
  return "burr: " + std::string(burrShapeName(wanted.shape)) + ", tip radius " + formatNumber(float(wanted.tipRadius * 1e3)) +
         " mm";
}

}  // namespace millsim
