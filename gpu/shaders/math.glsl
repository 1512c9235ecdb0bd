// The GLSL twin of core/math/math.h (constants, luminance, Frame) and of glm's vector helpers, in
// glm's operation order and `precise` (no fma contraction; the C++ is built without fma), so that
// GPU code that calls these reproduces the CPU's bits wherever the GPU's sqrt and division do.
// Call glm_dot / glm_cross / glm_length / glm_normalize wherever bits matter: the GLSL built-ins
// evaluate in the driver's order.
#ifndef SST_GPU_SHADERS_MATH_GLSL
#define SST_GPU_SHADERS_MATH_GLSL

const float kPi = 3.14159265358979323846;
const float kInvPi = 0.31830988618379067154;
#define kInf uintBitsToFloat(0x7F800000u)

float glm_dot(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

vec3 glm_cross(vec3 x, vec3 y) {
  precise vec3 r = vec3(x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y);
  return r;
}

float glm_length(vec3 v) { return sqrt(glm_dot(v, v)); }

// glm::normalize: v * inversesqrt(dot(v, v)), glm's inversesqrt being 1 / sqrt.
vec3 glm_normalize(vec3 v) {
  precise float inv = 1.0 / sqrt(glm_dot(v, v));
  precise vec3 r = v * inv;
  return r;
}

// Rec. 709 luminance, as core/math/math.h.
float luminance(vec3 c) {
  precise float r = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
  return r;
}

float max_component(vec3 v) { return max(v.x, max(v.y, v.z)); }

bool is_finite(float x) { return !isinf(x) && !isnan(x); }
bool is_finite3(vec3 v) { return is_finite(v.x) && is_finite(v.y) && is_finite(v.z); }

// Orthonormal basis around n (Duff et al. 2017), as sst::Frame.
struct Frame {
  vec3 t, b, n;
};

Frame frame_from_normal(vec3 n) {
  // std::copysign(1, n.z): the sign bit decides, so -0.0 gives -1 as on the CPU.
  float sign = (floatBitsToUint(n.z) & 0x80000000u) != 0u ? -1.0 : 1.0;
  precise float a = -1.0 / (sign + n.z);
  precise float bb = n.x * n.y * a;
  Frame f;
  precise vec3 t = vec3(1.0 + sign * n.x * n.x * a, sign * bb, -sign * n.x);
  precise vec3 b = vec3(bb, sign + n.y * n.y * a, -n.y);
  f.t = t;
  f.b = b;
  f.n = n;
  return f;
}

vec3 frame_to_local(Frame f, vec3 v) { return vec3(glm_dot(v, f.t), glm_dot(v, f.b), glm_dot(v, f.n)); }

vec3 frame_to_world(Frame f, vec3 v) {
  precise vec3 r = v.x * f.t + v.y * f.b + v.z * f.n;
  return r;
}

// core/rng/sobol_sampler.h: reuse a uniform after it chose between two options with probability p.
float remap_below(float u, float p) { return min(u / p, 0.99999994); }
float remap_above(float u, float p) {
  precise float r = (u - p) / (1.0 - p);
  return min(r, 0.99999994);
}

#endif
