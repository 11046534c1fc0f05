// Contact shadows (shaders/contact_shadow.frag): a short screen-space march towards the light that
// any technique writing a visibility buffer can multiply in after its own passes. Its parameters
// are declared here once (contact, contact-rays, contact-steps, contact-length,
// contact-thickness); the single-view map techniques take them (the `*-contact` presets turn it on).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gl/program_cache.h"
#include "pipeline/technique.h"

namespace penumbra::shadow_map {

struct ContactOptions {
  bool enabled = false;
  int rays = 4;             // rays a pixel, to its light samples (light_rays.glsl)
  int steps = 8;            // G-buffer samples along each
  double length = 0.05;     // the march's length: this fraction of the screen's height at the receiver's depth
  double thickness = 0.02;  // a surface nearer the camera than a step by at most this x its distance hides it
};

std::vector<ParamSpec> contactParams(const ContactOptions& preset);
ContactOptions readContactOptions(const TechniqueArgs& args);

class ContactShadows {
 public:
  explicit ContactShadows(const ContactOptions& o) : o_(o) {}
  bool enabled() const { return o_.enabled; }
  // Multiplies pass.visibility by the contact factor (stage "<technique> contact shadows").
  void apply(LightPass& pass, const std::string& technique);
  void addStatistics(std::vector<std::pair<std::string, double>>& out) const;

 private:
  ContactOptions o_;
  gl::ProgramCache programs_;
};

}  // namespace penumbra::shadow_map
