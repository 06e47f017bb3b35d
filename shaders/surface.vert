#version 330 core
// Lit surfaces: cloth, obstacles, arrows and ghosts. Lighting happens in view space.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in float scalar;  // per-vertex value for the colour map

uniform mat4 viewMatrix;
uniform mat4 projectionMatrix;

out vec3 viewPosition;
out vec3 viewNormal;
out float vertexScalar;

void main() {
  vec4 p = viewMatrix * vec4(position, 1.0);
  viewPosition = p.xyz;
  // The view matrix is a rigid motion, so it maps normals as it maps directions.
  viewNormal = mat3(viewMatrix) * normal;
  vertexScalar = scalar;
  gl_Position = projectionMatrix * p;
}
