#version 330 core
// Screen-space discs at vertices: fixed and handle vertices, targets, contact nodes.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;

uniform mat4 viewMatrix;
uniform mat4 projectionMatrix;
uniform float pointSize;  // diameter in pixels
uniform float depthBias;  // scene units toward the eye, so a marker is not buried in its surface
uniform bool orthographic;

out vec3 pointColor;

void main() {
  vec4 p = viewMatrix * vec4(position, 1.0);
  // Moving along the view ray keeps the marker on the same pixel.
  if (orthographic)
    p.z += depthBias;
  else
    p.xyz -= normalize(p.xyz) * min(depthBias, 0.5 * length(p.xyz));
  gl_Position = projectionMatrix * p;
  gl_PointSize = pointSize;
  pointColor = color;
}
