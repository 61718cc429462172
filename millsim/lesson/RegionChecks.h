#pragma once
// What `millsim check` (and every load) says about a lesson's assessment
// regions before anything runs: a region naming a tissue no VolumeObject has.
namespace millsim {

class Scene;
class DiagnosticSink;

void checkRegions(const Scene& scene, DiagnosticSink& sink);

}  // namespace millsim
