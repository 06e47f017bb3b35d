#version 330 core
// A disc; shaded like a small sphere for markers, or flat (the exact colour) for contact
// branches, so an image can be checked pixel by pixel.

in vec3 pointColor;
uniform bool shaded;
out vec4 fragColor;

const vec3 keyLight = normalize(vec3(-0.35, 0.55, 0.75));

void main() {
  vec2 q = 2.0 * gl_PointCoord - 1.0;
  float r2 = dot(q, q);
  if (r2 > 1.0) discard;
  if (!shaded) {
    fragColor = vec4(pointColor, 1.0);
    return;
  }
  vec3 n = vec3(q.x, -q.y, sqrt(1.0 - r2));  // gl_PointCoord grows downwards
  float diffuse = max(dot(n, keyLight), 0.0);
  float specular = 0.3 * pow(max(dot(n, normalize(keyLight + vec3(0.0, 0.0, 1.0))), 0.0), 32.0);
  fragColor = vec4(pointColor * (0.35 + 0.65 * diffuse) + vec3(specular), 1.0);
}
