#version 330 core
// Two-sided lighting: the back of a surface gets its own colour and a flipped normal, so a
// cloth's two sides are told apart and both are lit.

in vec3 viewPosition;
in vec3 viewNormal;
in float vertexScalar;

uniform vec3 frontColor;
uniform vec3 backColor;
uniform bool useColorMap;
uniform sampler2D colorMap;  // 256 x 1
uniform float scalarLow;
uniform float scalarHigh;
uniform float opacity;
uniform bool orthographic;

out vec4 fragColor;

const vec3 keyLight = normalize(vec3(-0.35, 0.55, 0.75));  // upper left, behind the viewer
const vec3 fillLight = normalize(vec3(0.6, 0.1, 0.5));     // right

void main() {
  vec3 n = length(viewNormal) > 1e-12 ? normalize(viewNormal) : vec3(0.0, 0.0, 1.0);
  vec3 base = frontColor;
  if (!gl_FrontFacing) {
    n = -n;
    base = backColor;
  }
  if (useColorMap) {
    float t = clamp((vertexScalar - scalarLow) / max(scalarHigh - scalarLow, 1e-30), 0.0, 1.0);
    base = texture(colorMap, vec2((t * 255.0 + 0.5) / 256.0, 0.5)).rgb;
  }
  vec3 toEye = orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-viewPosition);
  // Key, fill and a weak headlight, so surfaces turned away from the key light keep their
  // shape and colour instead of going black.
  float diffuse = 0.52 * max(dot(n, keyLight), 0.0) + 0.20 * max(dot(n, fillLight), 0.0) +
                  0.18 * max(dot(n, toEye), 0.0);
  float specular = 0.14 * pow(max(dot(n, normalize(keyLight + toEye)), 0.0), 48.0);
  fragColor = vec4(base * (0.34 + diffuse) + vec3(specular), opacity);
}
