// Float functions whose GPU built-ins are too coarse to reproduce the CPU (glibc): asin, atan2,
// sin and cos within 1 ulp of glibc's asinf/atan2f/sinf/cosf (90-98% of arguments bit-equal).
// Vulkan leaves the built-ins' precision loose: lavapipe's asin is off by up to ~1e-4 absolute,
// which the spherical-triangle sampler (gpu/shaders/spherical_triangle.glsl) amplifies by
// pi / solid angle into percent errors of its pdf; NVIDIA's sin and cos are hardware
// approximations with absolute (not relative) error bounds. Also float-float helpers (value =
// hi + lo) for the double arithmetic of the light pick (gpu/shaders/light_sampler.glsl).
// Everything is `precise` and uses only + - * (correctly rounded in Vulkan), sqrt and one
// division per call, whose small errors the last steps absorb.
#ifndef SST_GPU_SHADERS_ACCURATE_MATH_GLSL
#define SST_GPU_SHADERS_ACCURATE_MATH_GLSL

// ---- float-float arithmetic (Knuth's two-sum, Dekker's product with Veltkamp's split) ----------

vec2 ff_two_sum(float a, float b) {
  precise float s = a + b;
  precise float bb = s - a;
  precise float e = (a - (s - bb)) + (b - bb);
  return vec2(s, e);
}

vec2 ff_sub(vec2 a, vec2 b) {
  vec2 s = ff_two_sum(a.x, -b.x);
  precise float lo = s.y + (a.y - b.y);
  return ff_two_sum(s.x, lo);
}

vec2 ff_split(float a) {
  precise float t = 4097.0 * a;
  precise float hi = t - (t - a);
  precise float lo = a - hi;
  return vec2(hi, lo);
}

// a * b as p + e exactly (for |a b| far from overflow and underflow).
vec2 ff_two_prod(float a, float b) {
  precise float p = a * b;
  vec2 as = ff_split(a), bs = ff_split(b);
  precise float e = ((as.x * bs.x - p) + as.x * bs.y + as.y * bs.x) + as.y * bs.y;
  return vec2(p, e);
}

// a / b rounded to float, for b > 0: a first quotient, then one correction from the exact
// remainder, so the GPU's approximate division does not decide the last bit.
float ff_div_to_float(vec2 a, vec2 b) {
  float q1 = a.x / b.x;
  vec2 p = ff_two_prod(b.x, q1);
  vec2 r = ff_two_sum(a.x, -p.x);
  precise float r_lo = r.y - p.y + a.y - q1 * b.y;
  vec2 rem = ff_two_sum(r.x, r_lo);
  float q2 = rem.x / b.x;
  precise float q = q1 + q2;
  return q;
}

// ---- asin and atan2 -----------------------------------------------------------------------------
// Polynomials fitted (Chebyshev, mpmath.chebyfit) to (f(x) - x) / x^3 in t = x^2: asin on
// x in [0, 1/2] (abs. error 4e-9), atan on x in [0, 1] (4e-10). Larger arguments are reduced
// with pi/2 split into hi + lo floats.

const float kAccuratePiO2Hi = 1.57079637;        // float(pi / 2)
const float kAccuratePiO2Lo = -4.37113883e-08;   // pi / 2 - kAccuratePiO2Hi
const float kAccuratePiHi = 3.14159274;          // float(pi)
const float kAccuratePiLo = -8.74227766e-08;     // pi - kAccuratePiHi

// (asin(x) - x) for x in [0, 1/2], t = x * x (Horner's rule, highest degree first).
float accurate_asin_tail(float x, float t) {
  precise float p = 3.369084746e-02;
  p = p * t + 1.714923792e-02;
  p = p * t + 3.110066243e-02;
  p = p * t + 4.459940270e-02;
  p = p * t + 7.500094175e-02;
  p = p * t + 1.666666567e-01;
  precise float r = x * t * p;
  return r;
}

// (atan(q) - q) for q in [0, 1], t = q * q.
float accurate_atan_tail(float q, float t) {
  precise float p = -9.362994460e-04;
  p = p * t + 6.207254715e-03;
  p = p * t - 1.926108077e-02;
  p = p * t + 3.832744434e-02;
  p = p * t - 5.760715902e-02;
  p = p * t + 7.417497039e-02;
  p = p * t - 9.036742151e-02;
  p = p * t + 1.110470667e-01;
  p = p * t - 1.428531855e-01;
  p = p * t + 1.999998987e-01;
  p = p * t - 3.333333433e-01;
  precise float r = q * t * p;
  return r;
}

float accurate_asin(float x) {
  float a = abs(x);
  float r;
  if (a <= 0.5) {
    precise float t = a * a;
    precise float s = a + accurate_asin_tail(a, t);
    r = s;
  } else {
    // asin(a) = pi/2 - 2 asin(z), z = sqrt((1 - a) / 2) (exact argument: 1 - a is exact here);
    // z's rounding error is recovered from the exact residual w - z^2.
    precise float w = (1.0 - a) * 0.5;
    float z = sqrt(w);
    vec2 zz = ff_two_prod(z, z);
    precise float residual = (w - zz.x) - zz.y;
    precise float z_lo = residual / (2.0 * z);
    precise float t = z * z;
    precise float tail = accurate_asin_tail(z, t) + z_lo;
    precise float s = kAccuratePiO2Hi - (2.0 * z - (kAccuratePiO2Lo - 2.0 * tail));
    r = z > 0.0 ? s : kAccuratePiO2Hi;
  }
  return x < 0.0 ? -r : r;  // NaN stays NaN through the branches above
}

// atan2(y, x) as std::atan2 for finite arguments (atan2(0, 0) = 0 or pi by the signs).
float accurate_atan2(float y, float x) {
  float ay = abs(y), ax = abs(x);
  bool swap = ay > ax;
  float q = swap ? ax / ay : (ax > 0.0 ? ay / ax : 0.0);
  precise float t = q * q;
  precise float r = q + accurate_atan_tail(q, t);
  if (swap) {
    precise float s = kAccuratePiO2Hi + (kAccuratePiO2Lo - r);
    r = s;
  }
  if (x < 0.0 || (x == 0.0 && (floatBitsToUint(x) & 0x80000000u) != 0u)) {
    precise float s = kAccuratePiHi + (kAccuratePiLo - r);
    r = s;
  }
  return (floatBitsToUint(y) & 0x80000000u) != 0u ? -r : r;
}

// ---- sin and cos ----------------------------------------------------------------------------------
// Within 1 ulp of glibc's sinf/cosf (98% of arguments bit-equal) for |x| < 6000: x - k pi/2 in
// float-float (Cody-Waite, pi/2 in three parts, the first two of 12 bits so that k times them is
// exact), then polynomials fitted on [-pi/4, pi/4] (abs. error 3e-11 and 2e-12).

struct AccurateReduced {
  uint quadrant;  // k mod 4
  float hi;       // x - k pi/2 = hi + lo, |hi| <= pi/4 (about)
  float lo;
};

AccurateReduced accurate_reduce(float x) {
  const float p1 = 1.5703125;         // pi/2 = p1 + p2 + p3
  const float p2 = 4.837512970e-04;
  const float p3 = 7.549790126e-08;
  precise float kf = floor(x * 0.636619747 + 0.5);  // 0.636619747 = float(2 / pi)
  precise float r = x - kf * p1;
  precise float m2 = kf * p2;
  vec2 h = ff_two_sum(r, -m2);
  precise float lo = h.y - kf * p3;
  vec2 n = ff_two_sum(h.x, lo);
  AccurateReduced a;
  a.quadrant = uint(int(kf) & 3);
  a.hi = n.x;
  a.lo = n.y;
  return a;
}

// sin(hi + lo) for |hi + lo| <= pi/4.
float accurate_sin_reduced(float h, float l) {
  precise float t = h * h;
  precise float p = 2.724992555e-06;
  p = p * t - 1.984008704e-04;
  p = p * t + 8.333331905e-03;
  p = p * t - 1.666666716e-01;
  precise float s = h + (l + h * t * p);
  return s;
}

// cos(hi + lo) for |hi + lo| <= pi/4: 1 - t/2 in float-float, then the polynomial's t^2 tail.
float accurate_cos_reduced(float h, float l) {
  vec2 t = ff_two_prod(h, h);
  precise float t_lo = t.y + 2.0 * h * l;
  precise float half_hi = t.x * 0.5, half_lo = t_lo * 0.5;
  vec2 w = ff_two_sum(1.0, -half_hi);
  precise float p = -2.730095900e-07;
  p = p * t.x + 2.480059993e-05;
  p = p * t.x - 1.388888806e-03;
  p = p * t.x + 4.166666791e-02;
  precise float c = w.x + (w.y + (t.x * t.x * p - half_lo));
  return c;
}

float accurate_sin(float x) {
  AccurateReduced a = accurate_reduce(x);
  float s = (a.quadrant & 1u) == 0u ? accurate_sin_reduced(a.hi, a.lo) : accurate_cos_reduced(a.hi, a.lo);
  return a.quadrant >= 2u ? -s : s;
}

float accurate_cos(float x) {
  AccurateReduced a = accurate_reduce(x);
  float c = (a.quadrant & 1u) == 0u ? accurate_cos_reduced(a.hi, a.lo) : accurate_sin_reduced(a.hi, a.lo);
  return a.quadrant == 1u || a.quadrant == 2u ? -c : c;
}

#endif  // SST_GPU_SHADERS_ACCURATE_MATH_GLSL
