#version 330 core

in vec3 legendColor;
in float legendValue;

uniform sampler2D colorMap;

out vec4 fragColor;

void main() {
  vec3 c = legendColor;
  if (legendValue >= 0.0) c = texture(colorMap, vec2((clamp(legendValue, 0.0, 1.0) * 255.0 + 0.5) / 256.0, 0.5)).rgb;
  fragColor = vec4(c, 1.0);
}
