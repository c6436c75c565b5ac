#version 430
// Reconstructs a BCC volume with M7 at a batch of points: the evaluator comes from
//   boxgen emit m7 --name m7 --target glsl --out .
// and is pasted (or #include'd by the application's loader) where marked below. The volume is an
// SSBO over a box of integer points [lo, lo + side)^3 (BCC samples at the points with equal
// parity; the others are never fetched); the application binds points and receives values,
// gradients and Hessians.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Values { vec4 value_gradient[]; };
layout(std430, binding = 2) writeonly buffer Hessians { mat4 hessians[]; };
layout(std430, binding = 3) readonly buffer Volume { float samples[]; };
uniform int point_count;
uniform ivec3 lo;
uniform int side;

// The application's fetch, defined before the emitted text.
float m7_fetch(ivec3 j) {
  ivec3 k = clamp(j - lo, ivec3(0), ivec3(side - 1));
  return samples[k.x + side * (k.y + side * k.z)];
}

// ---- the text of m7.glsl goes here ----

void main() {
  int p = int(gl_GlobalInvocationID.x);
  if (p >= point_count) return;
  vec3 g;
  mat3 h;
  float v = m7_value_gradient_hessian(points[p].xyz, g, h);
  value_gradient[p] = vec4(v, g);
  hessians[p] = mat4(h);
}
