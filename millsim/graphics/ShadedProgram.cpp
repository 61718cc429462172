#include "millsim/graphics/ShadedProgram.h"

#include <algorithm>
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
layout(location = 3) in vec2 aTexCoord;
uniform mat4 uModel;
uniform mat4 uViewProj;
uniform mat3 uNormalMatrix;
uniform int uClipCount;
uniform vec4 uClip[6];
out vec3 vWorld;
out vec3 vNormal;
out vec3 vColour;
out vec2 vTexCoord;
out float gl_ClipDistance[6];
void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  vColour = aColour;
  vTexCoord = aTexCoord;
  for (int i = 0; i < 6; ++i) gl_ClipDistance[i] = i < uClipCount ? dot(uClip[i], world) : 1.0;
  gl_Position = uViewProj * world;
}
)";

// Two-sided: a surface seen from behind (the inside of a clipped tooth, the
// far wall of a hole) is lit with its normal turned to the viewer. Lit by
// MillSim's headlight and fill light (NavigationInfo.headlight) and by the
// scene's lights, X3D's way: diffuse and specular per light, fading with
// distance and outside a spot's beam. uTexture: 0 none, 1 an RGB(A) image
// replaces the colour, 2 a grey image modulates it, 3 a glyph's coverage is
// the alpha (Text), 4 a cut's section (CutSection): the image's colour where
// its filtered material fraction (alpha) is at least ½, nothing elsewhere.
const char* kFragment = R"(#version 330 core
in vec3 vWorld;
in vec3 vNormal;
in vec3 vColour;
in vec2 vTexCoord;
uniform vec3 uEye;
uniform vec3 uHead;
uniform vec3 uFill;
uniform int uHeadOn;
uniform vec3 uAmbientLight;
uniform int uLightCount;
uniform int uLightMask;
uniform vec4 uLightPos[8];
uniform vec3 uLightColour[8];
uniform vec4 uLightAtt[8];
uniform vec4 uLightSpot[8];
uniform vec2 uLightCone[8];
uniform vec3 uSpecular;
uniform float uShininess;
uniform vec3 uEmissive;
uniform float uAmbient;
uniform int uTint;
uniform float uOpacity;
uniform int uTexture;
uniform sampler2D uImage;
out vec4 fragColour;
void main() {
  vec3 n = normalize(vNormal);
  vec3 v = normalize(uEye - vWorld);
  if (dot(n, v) < 0.0) n = -n;
  vec3 base = vColour;
  float alpha = uOpacity;
  if (uTexture == 1 || uTexture == 2) {
    vec4 texel = texture(uImage, vTexCoord);
    base = uTexture == 1 ? texel.rgb : base * texel.r;
    alpha *= texel.a;
  } else if (uTexture == 3) {
    alpha *= texture(uImage, vTexCoord).r;
    if (alpha < 0.02) discard;
  } else if (uTexture == 4) {
    vec4 texel = texture(uImage, vTexCoord);
    if (texel.a < 0.5) discard;
    base = texel.rgb;
  }
  if (uTint != 0 && !gl_FrontFacing) base = base * vec3(0.55, 0.35, 0.32);
  vec3 c = base * uAmbient * uAmbientLight + uEmissive;
  if (uHeadOn != 0) {
    float head = max(dot(n, uHead), 0.0), fill = max(dot(n, uFill), 0.0);
    float sHead = head > 0.0 ? pow(max(dot(n, normalize(uHead + v)), 0.0), uShininess) : 0.0;
    float sFill = fill > 0.0 ? pow(max(dot(n, normalize(uFill + v)), 0.0), uShininess) : 0.0;
    c += base * (0.70 * head + 0.40 * fill) + uSpecular * (sHead + 0.5 * sFill);
  }
  for (int i = 0; i < uLightCount; ++i) {
    if ((uLightMask & (1 << i)) == 0) continue;  // a scoped light that does not reach this object
    vec3 l = uLightPos[i].xyz;
    float weight = 1.0;
    if (uLightPos[i].w != 0.0) {
      vec3 d = uLightPos[i].xyz - vWorld;
      float dist = length(d);
      if (dist > uLightAtt[i].w) continue;
      l = d / max(dist, 1e-12);
      weight = 1.0 / max(uLightAtt[i].x + uLightAtt[i].y * dist + uLightAtt[i].z * dist * dist, 1.0);
      if (uLightSpot[i].w > 0.0) {  // a spot: full inside beamWidth, fading linearly to cutOffAngle
        float angle = acos(clamp(dot(-l, uLightSpot[i].xyz), -1.0, 1.0));
        float beam = uLightCone[i].x, cutOff = uLightCone[i].y;
        if (angle >= cutOff) continue;
        if (angle > beam) weight *= (cutOff - angle) / max(cutOff - beam, 1e-6);
      }
    }
    float diffuse = max(dot(n, l), 0.0);
    float spec = diffuse > 0.0 ? pow(max(dot(n, normalize(l + v)), 0.0), uShininess) : 0.0;
    c += weight * uLightColour[i] * (base * diffuse + uSpecular * spec);
  }
  fragColour = vec4(clamp(c, 0.0, 1.0), alpha);
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
  uHeadOn_ = u("uHeadOn"), uAmbientLight_ = u("uAmbientLight"), uLightCount_ = u("uLightCount");
  uLightPos_ = u("uLightPos"), uLightColour_ = u("uLightColour"), uLightAtt_ = u("uLightAtt");
  uLightSpot_ = u("uLightSpot"), uLightCone_ = u("uLightCone"), uTexture_ = u("uTexture"), uImage_ = u("uImage");
  uLightMask_ = u("uLightMask");
}

ShadedProgram::~ShadedProgram() { glDeleteProgram(program_); }

void ShadedProgram::use(const Camera& camera, const glm::vec3& headlight, const glm::vec3& fillLight, bool headlightOn,
                        const std::vector<DrawLight>& lights) {
  glUseProgram(program_);
  glUniform1i(uImage_, 0);
  glUniform1i(uTexture_, 0);
  glUniform1i(uHeadOn_, headlightOn ? 1 : 0);
  // The headlight brings MillSim's usual ambient term; each light adds its own.
  glm::vec3 ambient(headlightOn ? 1.f : 0.f);
  const int n = std::min(int(lights.size()), kMaxLights);
  glm::vec4 pos[kMaxLights], att[kMaxLights], spot[kMaxLights];
  glm::vec3 colour[kMaxLights];
  glm::vec2 cone[kMaxLights];
  globalLights_ = 0;
  for (int i = 0; i < n; ++i) {
    const DrawLight& l = lights[std::size_t(i)];
    if (l.global) globalLights_ |= 1u << i;
    ambient += l.ambient;
    colour[i] = l.colour;
    const bool directional = l.kind == DrawLight::Kind::Directional;
    pos[i] = directional ? glm::vec4(glm::vec3(-l.direction), 0.f) : glm::vec4(glm::vec3(l.position), 1.f);
    att[i] = glm::vec4(l.attenuation, float(l.radius));
    spot[i] = glm::vec4(glm::vec3(l.direction), l.kind == DrawLight::Kind::Spot ? 1.f : 0.f);
    cone[i] = glm::vec2(l.beamWidth, l.cutOffAngle);
  }
  glUniform3fv(uAmbientLight_, 1, glm::value_ptr(ambient));
  glUniform1i(uLightCount_, n);
  if (n > 0) {
    glUniform4fv(uLightPos_, n, glm::value_ptr(pos[0]));
    glUniform3fv(uLightColour_, n, glm::value_ptr(colour[0]));
    glUniform4fv(uLightAtt_, n, glm::value_ptr(att[0]));
    glUniform4fv(uLightSpot_, n, glm::value_ptr(spot[0]));
    glUniform2fv(uLightCone_, n, glm::value_ptr(cone[0]));
  }
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
  glUniform1i(uTexture_, 0);  // setTexture() after this call turns a texture on
  glUniform1i(uLightMask_, int(globalLights_));  // setLights() after this call adds scoped lights
  // Attribute 2 without an array supplies one colour for the whole draw.
  if (colour) glVertexAttrib3fv(2, glm::value_ptr(*colour));
}

void ShadedProgram::setTexture(TextureMode mode) { glUniform1i(uTexture_, int(mode)); }

void ShadedProgram::setLights(std::uint32_t mask) { glUniform1i(uLightMask_, int(mask)); }

}  // namespace millsim
