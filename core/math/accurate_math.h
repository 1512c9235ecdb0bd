// Float functions whose built-ins differ between the backends, written once for both: asin,
// atan2, sin and cos within 1 ulp of glibc's asinf/atan2f/sinf/cosf (90-98% of arguments
// bit-equal), so that the CPU and the GPU compute the same bits. Vulkan leaves the built-ins'
// precision loose: lavapipe's asin is off by up to ~1e-4 absolute, which the spherical-triangle
// sampler (core/sampling/spherical_triangle.h) amplifies by pi / solid angle into percent errors of
// its pdf; NVIDIA's sin and cos are hardware approximations with absolute error bounds. Also
// float-float helpers (value = hi + lo) for the double-width arithmetic of the light pick.
// Everything is precise and uses only + - * (correctly rounded on both sides), sqrt and one
// division per call, whose small errors the last steps absorb.
#ifndef SST_CORE_MATH_ACCURATE_MATH_H
#define SST_CORE_MATH_ACCURATE_MATH_H
#include "core/math/cpu_gpu.h"

SST_BEGIN

// ---- float-float arithmetic (Knuth's two-sum, Dekker's product with Veltkamp's split) ----------

SST_FUNC vec2 ff_two_sum(float a, float b) {
  SST_PRECISE float s = a + b;
  SST_PRECISE float bb = s - a;
  SST_PRECISE float e = (a - (s - bb)) + (b - bb);
  return vec2(s, e);
}

SST_FUNC vec2 ff_sub(vec2 a, vec2 b) {
  vec2 s = ff_two_sum(a.x, -b.x);
  SST_PRECISE float lo = s.y + (a.y - b.y);
  return ff_two_sum(s.x, lo);
}

SST_FUNC vec2 ff_split(float a) {
  SST_PRECISE float t = 4097.0f * a;
  SST_PRECISE float hi = t - (t - a);
  SST_PRECISE float lo = a - hi;
  return vec2(hi, lo);
}

// a * b as p + e exactly (for |a b| far from overflow and underflow).
SST_FUNC vec2 ff_two_prod(float a, float b) {
  SST_PRECISE float p = a * b;
  vec2 as = ff_split(a), bs = ff_split(b);
  SST_PRECISE float e = ((as.x * bs.x - p) + as.x * bs.y + as.y * bs.x) + as.y * bs.y;
  return vec2(p, e);
}

// a / b rounded to float, for b > 0: a first quotient, then one correction from the exact
// remainder, so the GPU's approximate division does not decide the last bit.
SST_FUNC float ff_div_to_float(vec2 a, vec2 b) {
  float q1 = a.x / b.x;
  vec2 p = ff_two_prod(b.x, q1);
  vec2 r = ff_two_sum(a.x, -p.x);
  SST_PRECISE float r_lo = r.y - p.y + a.y - q1 * b.y;
  vec2 rem = ff_two_sum(r.x, r_lo);
  float q2 = rem.x / b.x;
  SST_PRECISE float q = q1 + q2;
  return q;
}

// ---- asin and atan2 -----------------------------------------------------------------------------
// Polynomials fitted (Chebyshev, mpmath.chebyfit) to (f(x) - x) / x^3 in t = x^2: asin on
// x in [0, 1/2] (abs. error 4e-9), atan on x in [0, 1] (4e-10). Larger arguments are reduced
// with pi/2 split into hi + lo floats.

SST_CONSTANT float kAccuratePiO2Hi = 1.57079637f;        // float(pi / 2)
SST_CONSTANT float kAccuratePiO2Lo = -4.37113883e-08f;   // pi / 2 - kAccuratePiO2Hi
SST_CONSTANT float kAccuratePiHi = 3.14159274f;          // float(pi)
SST_CONSTANT float kAccuratePiLo = -8.74227766e-08f;     // pi - kAccuratePiHi

// (asin(x) - x) for x in [0, 1/2], t = x * x (Horner's rule, highest degree first).
SST_FUNC float accurate_asin_tail(float x, float t) {
  SST_PRECISE float p = 3.369084746e-02f;
  p = p * t + 1.714923792e-02f;
  p = p * t + 3.110066243e-02f;
  p = p * t + 4.459940270e-02f;
  p = p * t + 7.500094175e-02f;
  p = p * t + 1.666666567e-01f;
  SST_PRECISE float r = x * t * p;
  return r;
}

// (atan(q) - q) for q in [0, 1], t = q * q.
SST_FUNC float accurate_atan_tail(float q, float t) {
  SST_PRECISE float p = -9.362994460e-04f;
  p = p * t + 6.207254715e-03f;
  p = p * t - 1.926108077e-02f;
  p = p * t + 3.832744434e-02f;
  p = p * t - 5.760715902e-02f;
  p = p * t + 7.417497039e-02f;
  p = p * t - 9.036742151e-02f;
  p = p * t + 1.110470667e-01f;
  p = p * t - 1.428531855e-01f;
  p = p * t + 1.999998987e-01f;
  p = p * t - 3.333333433e-01f;
  SST_PRECISE float r = q * t * p;
  return r;
}

SST_FUNC float accurate_asin(float x) {
  float a = abs(x);
  float r;
  if (a <= 0.5f) {
    SST_PRECISE float t = a * a;
    SST_PRECISE float s = a + accurate_asin_tail(a, t);
    r = s;
  } else {
    // asin(a) = pi/2 - 2 asin(z), z = sqrt((1 - a) / 2) (exact argument: 1 - a is exact here);
    // z's rounding error is recovered from the exact residual w - z^2.
    SST_PRECISE float w = (1.0f - a) * 0.5f;
    float z = sqrt(w);
    vec2 zz = ff_two_prod(z, z);
    SST_PRECISE float residual = (w - zz.x) - zz.y;
    SST_PRECISE float z_lo = residual / (2.0f * z);
    SST_PRECISE float t = z * z;
    SST_PRECISE float tail = accurate_asin_tail(z, t) + z_lo;
    SST_PRECISE float s = kAccuratePiO2Hi - (2.0f * z - (kAccuratePiO2Lo - 2.0f * tail));
    r = z > 0.0f ? s : kAccuratePiO2Hi;
  }
  return x < 0.0f ? -r : r;  // NaN stays NaN through the branches above
}

// atan2(y, x) as std::atan2 for finite arguments (atan2(0, 0) = 0 or pi by the signs).
SST_FUNC float accurate_atan2(float y, float x) {
  float ay = abs(y), ax = abs(x);
  bool swap = ay > ax;
  float q = swap ? ax / ay : (ax > 0.0f ? ay / ax : 0.0f);
  SST_PRECISE float t = q * q;
  SST_PRECISE float r = q + accurate_atan_tail(q, t);
  if (swap) {
    SST_PRECISE float s = kAccuratePiO2Hi + (kAccuratePiO2Lo - r);
    r = s;
  }
  if (x < 0.0f || (x == 0.0f && (floatBitsToUint(x) & 0x80000000u) != 0u)) {
    SST_PRECISE float s = kAccuratePiHi + (kAccuratePiLo - r);
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

SST_FUNC AccurateReduced accurate_reduce(float x) {
  const float p1 = 1.5703125f;         // pi/2 = p1 + p2 + p3
  const float p2 = 4.837512970e-04f;
  const float p3 = 7.549790126e-08f;
  SST_PRECISE float kf = floor(x * 0.636619747f + 0.5f);  // 0.636619747 = float(2 / pi)
  SST_PRECISE float r = x - kf * p1;
  SST_PRECISE float m2 = kf * p2;
  vec2 h = ff_two_sum(r, -m2);
  SST_PRECISE float lo = h.y - kf * p3;
  vec2 n = ff_two_sum(h.x, lo);
  AccurateReduced a;
  a.quadrant = uint(int(kf) & 3);
  a.hi = n.x;
  a.lo = n.y;
  return a;
}

// sin(hi + lo) for |hi + lo| <= pi/4.
SST_FUNC float accurate_sin_reduced(float h, float l) {
  SST_PRECISE float t = h * h;
  SST_PRECISE float p = 2.724992555e-06f;
  p = p * t - 1.984008704e-04f;
  p = p * t + 8.333331905e-03f;
  p = p * t - 1.666666716e-01f;
  SST_PRECISE float s = h + (l + h * t * p);
  return s;
}

// cos(hi + lo) for |hi + lo| <= pi/4: 1 - t/2 in float-float, then the polynomial's t^2 tail.
SST_FUNC float accurate_cos_reduced(float h, float l) {
  vec2 t = ff_two_prod(h, h);
  SST_PRECISE float t_lo = t.y + 2.0f * h * l;
  SST_PRECISE float half_hi = t.x * 0.5f, half_lo = t_lo * 0.5f;
  vec2 w = ff_two_sum(1.0f, -half_hi);
  SST_PRECISE float p = -2.730095900e-07f;
  p = p * t.x + 2.480059993e-05f;
  p = p * t.x - 1.388888806e-03f;
  p = p * t.x + 4.166666791e-02f;
  SST_PRECISE float c = w.x + (w.y + (t.x * t.x * p - half_lo));
  return c;
}

SST_FUNC float accurate_sin(float x) {
  AccurateReduced a = accurate_reduce(x);
  float s = (a.quadrant & 1u) == 0u ? accurate_sin_reduced(a.hi, a.lo) : accurate_cos_reduced(a.hi, a.lo);
  return a.quadrant >= 2u ? -s : s;
}

SST_FUNC float accurate_cos(float x) {
  AccurateReduced a = accurate_reduce(x);
  float c = (a.quadrant & 1u) == 0u ? accurate_cos_reduced(a.hi, a.lo) : accurate_sin_reduced(a.hi, a.lo);
  return a.quadrant == 1u || a.quadrant == 2u ? -c : c;
}

// ---- log --------------------------------------------------------------------------------------
// Natural logarithm of a positive finite float within 1 ulp (the argument reduction and
// polynomial of fdlibm's logf, Sun Microsystems 1993): x = 2^k m with m in [sqrt(2)/2, sqrt(2)),
// log(m) = 2 atanh(f / (2 + f)), f = m - 1. x <= 0 gives -inf, as the sampling that calls it
// never passes.
SST_FUNC float accurate_log(float x) {
  if (!(x > 0.0f)) return -uintBitsToFloat(0x7F800000u);
  uint ix = floatBitsToUint(x);
  int k = 0;
  if (ix < 0x00800000u) {  // subnormal: scale by 2^25 first
    k = -25;
    SST_PRECISE float scaled = x * 33554432.0f;
    ix = floatBitsToUint(scaled);
  }
  k += int(ix >> 23u) - 127;
  ix &= 0x007fffffu;
  uint i = (ix + 0x4afb20u) & 0x800000u;  // 0x4afb20: mantissas above sqrt(2) take the next k
  SST_PRECISE float m = uintBitsToFloat(ix | (i ^ 0x3f800000u));
  k += int(i >> 23u);
  SST_PRECISE float f = m - 1.0f;
  SST_PRECISE float s = f / (2.0f + f);
  float dk = float(k);
  SST_PRECISE float z = s * s;
  SST_PRECISE float w = z * z;
  SST_PRECISE float t1 = w * (0.40000972152f + w * 0.24279078841f);
  SST_PRECISE float t2 = z * (0.66666662693f + w * 0.28498786688f);
  SST_PRECISE float r = t2 + t1;
  const float ln2_hi = 6.9313812256e-01f;
  const float ln2_lo = 9.0580006145e-06f;
  int hi_test = int(ix) - 0x30a3d0;  // f in about [-0.3, 0.4]: the cheaper of two forms
  int lo_test = 0x35c288 - int(ix);
  if ((hi_test | lo_test) > 0) {
    SST_PRECISE float hfsq = 0.5f * f * f;
    SST_PRECISE float v = dk * ln2_hi - ((hfsq - (s * (hfsq + r) + dk * ln2_lo)) - f);
    return v;
  }
  SST_PRECISE float v = dk * ln2_hi - ((s * (f - r) - dk * ln2_lo) - f);
  return v;
}

SST_END

#endif  // SST_CORE_MATH_ACCURATE_MATH_H
