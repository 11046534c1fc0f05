#include "techniques/common/shadow_map/contact.h"

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "pipeline/renderer.h"

namespace penumbra::shadow_map {

std::vector<ParamSpec> contactParams(const ContactOptions& o) {
  return {ParamSpec::boolean("contact", o.enabled,
                             "multiply in contact shadows: a short screen-space march towards the light"),
          ParamSpec::integer("contact-rays", o.rays, 1, 64, "contact shadows: rays a pixel, to its light samples"),
          ParamSpec::integer("contact-steps", o.steps, 1, 128, "contact shadows: G-buffer samples along each ray"),
          ParamSpec::number("contact-length", o.length, 0.0, 1.0,
                            "contact shadows: the march's length, as a fraction of the screen's height at the "
                            "receiver's depth"),
          ParamSpec::number("contact-thickness", o.thickness, 0.0, 1.0,
                            "contact shadows: a surface nearer the camera than a step by at most this x the step's "
                            "distance hides it")};
}

ContactOptions readContactOptions(const TechniqueArgs& args) {
  ContactOptions o;
  o.enabled = args.boolean("contact");
  o.rays = args.integer("contact-rays");
  o.steps = args.integer("contact-steps");
  o.length = args.number("contact-length");
  o.thickness = args.number("contact-thickness");
  return o;
}

void ContactShadows::apply(LightPass& pass, const std::string& technique) {
  if (!o_.enabled) return;
  pass.timer.time(technique + " contact shadows", [&] {
    const gl::Program& p = programs_.get({"fullscreen.vert", "contact_shadow.frag"}, {});
    p.set("clipFromWorld", pass.gpu.clipFromWorld());
    p.set("eyePosition", pass.gpu.cameraPosition());
    p.set("tanHalfFovY", std::tan(glm::radians(pass.scene.camera.fovY) * 0.5f));
    p.set("contactRays", o_.rays);
    p.set("contactSteps", o_.steps);
    p.set("contactLength", float(o_.length));
    p.set("contactThickness", float(o_.thickness));
    gl::Framebuffer fbo({&pass.visibility}, nullptr);
    fbo.bind();
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR);  // visibility x factor
    pass.gpu.bindGBuffer();
    p.use();
    setLightUniforms(p, pass.light, pass.samples);
    gl::VertexArray vao = gl::VertexArray::create();
    vao.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
  });
}

void ContactShadows::addStatistics(std::vector<std::pair<std::string, double>>& out) const {
  out.emplace_back("contact shadows", o_.enabled ? 1.0 : 0.0);
  if (!o_.enabled) return;
  out.emplace_back("contact rays", o_.rays);
  out.emplace_back("contact steps", o_.steps);
  out.emplace_back("contact length", o_.length);
}

}  // namespace penumbra::shadow_map
