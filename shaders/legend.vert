#version 330 core
// Legend geometry in pixels from the top-left corner of the image.

layout(location = 0) in vec2 pixel;
layout(location = 1) in vec3 color;
layout(location = 2) in float mapValue;  // in [0, 1]: take the colour map; negative: take `color`

uniform vec2 viewportSize;

out vec3 legendColor;
out float legendValue;

void main() {
  legendColor = color;
  legendValue = mapValue;
  gl_Position = vec4(2.0 * pixel.x / viewportSize.x - 1.0, 1.0 - 2.0 * pixel.y / viewportSize.y, 0.0, 1.0);
}
