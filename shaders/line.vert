#version 330 core
// Lines (wireframe, ground grid, curves), widened to quads by line.geom.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;

uniform mat4 viewMatrix;
uniform mat4 projectionMatrix;

out vec3 vertexColor;

void main() {
  vertexColor = color;
  gl_Position = projectionMatrix * viewMatrix * vec4(position, 1.0);
}
