#include "millsim/graphics/ShadedProgram.h"

#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "millsim/graphics/GraphicsError.h"

namespace millsim {

namespace {

const char* kVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColour;
uniform mat4 uModel;
uniform mat4 uViewProj;
uniform mat3 uNormalMatrix;
uniform int uClipCount;
uniform vec4 uClip[6];
out vec3 vWorld;
out vec3 vNormal;
out vec3 vColour;
out float gl_ClipDistance[6];
void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  vColour = aColour;
  for (int i = 0; i < 6; ++i) gl_ClipDistance[i] = i < uClipCount ? dot(uClip[i], world) : 1.0;
  gl_Position = uViewProj * world;
}
)";

// Two-sided: a surface seen from behind (the inside of a clipped tooth, the
// far wall of a hole) is lit with its normal turned to the viewer.
const char* kFragment = R"(#version 330 core
in vec3 vWorld;
in vec3 vNormal;
in vec3 vColour;
uniform vec3 uEye;
uniform vec3 uHead;
uniform vec3 uFill;
uniform vec3 uSpecular;
uniform float uShininess;
uniform vec3 uEmissive;
uniform float uAmbient;
uniform int uTint;
uniform float uOpacity;
out vec4 fragColour;
void main() {
  vec3 n = normalize(vNormal);
  vec3 v = normalize(uEye - vWorld);
  if (dot(n, v) < 0.0) n = -n;
  vec3 base = vColour;
  if (uTint != 0 && !gl_FrontFacing) base = base * vec3(0.55, 0.35, 0.32);
  float head = max(dot(n, uHead), 0.0), fill = max(dot(n, uFill), 0.0);
  float sHead = head > 0.0 ? pow(max(dot(n, normalize(uHead + v)), 0.0), uShininess) : 0.0;
  float sFill = fill > 0.0 ? pow(max(dot(n, normalize(uFill + v)), 0.0), uShininess) : 0.0;
  vec3 c = base * (uAmbient + 0.70 * head + 0.40 * fill) + uSpecular * (sHead + 0.5 * sFill) + uEmissive;
  fragColour = vec4(clamp(c, 0.0, 1.0), uOpacity);
}
)";

unsigned compile(GLenum stage, const char* source, const char* name) {
  const unsigned s = glCreateShader(stage);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    throw GraphicsError(std::string("the ") + name + " shader does not compile: " + log);
  }
  return s;
}

}  // namespace

ShadedProgram::ShadedProgram() {
  const unsigned vs = compile(GL_VERTEX_SHADER, kVertex, "vertex");
  const unsigned fs = compile(GL_FRAGMENT_SHADER, kFragment, "fragment");
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    throw GraphicsError(std::string("the shader program does not link: ") + log);
  }
  auto u = [this](const char* n) { return glGetUniformLocation(program_, n); };
  uModel_ = u("uModel"), uViewProj_ = u("uViewProj"), uNormalMatrix_ = u("uNormalMatrix"), uEye_ = u("uEye");
  uHead_ = u("uHead"), uFill_ = u("uFill"), uSpecular_ = u("uSpecular"), uShininess_ = u("uShininess");
  uEmissive_ = u("uEmissive"), uAmbient_ = u("uAmbient"), uTint_ = u("uTint"), uClipCount_ = u("uClipCount");
  uClip_ = u("uClip"), uOpacity_ = u("uOpacity");
}

ShadedProgram::~ShadedProgram() { glDeleteProgram(program_); }

void ShadedProgram::use(const Camera& camera, const glm::vec3& headlight, const glm::vec3& fillLight) {
  glUseProgram(program_);
  const glm::mat4 viewProj(camera.projection * camera.view);
  glUniformMatrix4fv(uViewProj_, 1, GL_FALSE, glm::value_ptr(viewProj));
  const glm::vec3 eye(camera.eye());
  glUniform3fv(uEye_, 1, glm::value_ptr(eye));
  glUniform3fv(uHead_, 1, glm::value_ptr(headlight));
  glUniform3fv(uFill_, 1, glm::value_ptr(fillLight));
}

void ShadedProgram::setObject(const glm::dmat4& model, const DrawMaterial& m, const glm::vec3* colour, bool tintInside,
                              const ClipPlanes& clipPlanes) {
  const glm::mat4 fm(model);
  const glm::mat3 normalMatrix(glm::transpose(glm::inverse(glm::dmat3(model))));
  glUniformMatrix4fv(uModel_, 1, GL_FALSE, glm::value_ptr(fm));
  glUniformMatrix3fv(uNormalMatrix_, 1, GL_FALSE, glm::value_ptr(normalMatrix));
  glUniform3fv(uSpecular_, 1, glm::value_ptr(m.specular));
  glUniform1f(uShininess_, std::max(1.f, m.shininess * 128.f));  // X3D scales shininess by 128
  glUniform3fv(uEmissive_, 1, glm::value_ptr(m.emissive));
  glUniform1f(uAmbient_, m.ambient);
  glUniform1i(uTint_, tintInside ? 1 : 0);
  glUniform1f(uOpacity_, 1.f - m.transparency);
  const int n = std::min(int(clipPlanes.size()), kMaxClipPlanes);
  glm::vec4 planes[kMaxClipPlanes];
  for (int i = 0; i < n; ++i) planes[i] = glm::vec4(clipPlanes[std::size_t(i)]);
  glUniform1i(uClipCount_, n);
  if (n > 0) glUniform4fv(uClip_, n, glm::value_ptr(planes[0]));
  // Attribute 2 without an array supplies one colour for the whole draw.
  if (colour) glVertexAttrib3fv(2, glm::value_ptr(*colour));
}

}  // namespace millsim
