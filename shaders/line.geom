#version 330 core
// Turns each line into a screen-space quad `lineWidth` pixels wide: core profile OpenGL
// guarantees only one-pixel lines.

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

in vec3 vertexColor[];
out vec3 lineColor;

uniform vec2 viewportSize;  // pixels
uniform float lineWidth;    // pixels

void main() {
  vec4 a = gl_in[0].gl_Position;
  vec4 b = gl_in[1].gl_Position;
  vec3 ca = vertexColor[0];
  vec3 cb = vertexColor[1];
  // Clip against the near plane before the perspective divide: a ground line passing behind
  // the camera would otherwise flip through infinity.
  float da = a.z + a.w;
  float db = b.z + b.w;
  if (da < 0.0 && db < 0.0) return;
  if (da < 0.0) {
    float t = da / (da - db);
    a = mix(a, b, t);
    ca = mix(ca, cb, t);
  } else if (db < 0.0) {
    float t = db / (db - da);
    b = mix(b, a, t);
    cb = mix(cb, ca, t);
  }
  vec2 pa = a.xy / a.w * 0.5 * viewportSize;
  vec2 pb = b.xy / b.w * 0.5 * viewportSize;
  vec2 d = pb - pa;
  vec2 dir = length(d) > 1e-6 ? normalize(d) : vec2(1.0, 0.0);
  vec2 offset = vec2(-dir.y, dir.x) * (0.5 * lineWidth) / (0.5 * viewportSize);  // in NDC
  lineColor = ca;
  gl_Position = vec4(a.xy + offset * a.w, a.zw);
  EmitVertex();
  lineColor = ca;
  gl_Position = vec4(a.xy - offset * a.w, a.zw);
  EmitVertex();
  lineColor = cb;
  gl_Position = vec4(b.xy + offset * b.w, b.zw);
  EmitVertex();
  lineColor = cb;
  gl_Position = vec4(b.xy - offset * b.w, b.zw);
  EmitVertex();
  EndPrimitive();
}
