// What a triangle's vertices give a point of it at barycentrics b, in the common subset of C++ and
// GLSL (core/math/cpu_gpu.h): interpolated positions, uvs and COLOR_0, textures, and the
// material's alpha with the alpha test that every ray query applies (core/accel/bvh_traverse.h's
// BVH_ALPHA_TEST, Embree's filter functions in core/accel/embree_accel.cpp) and that shading
// builds on (core/shading/surface_eval.h). The scene is read through the SCENE_* hooks that
// core/shading/surface_eval.h lists (core/scene/scene_access.h on the CPU,
// gpu/shaders/surface.glsl on the GPU), defined before this file is included.
#ifndef SST_CORE_SCENE_TRIANGLE_ATTRIBUTES_H
#define SST_CORE_SCENE_TRIANGLE_ATTRIBUTES_H
#include "core/math/vector_math.h"
#include "core/scene/scene_layout.h"

SST_BEGIN

// (1 - b.x - b.y) * a + b.x * b1 + b.y * b2: a point of the triangle (a, b1, b2) at barycentrics b.
SST_FUNC vec3 barycentric_mix3(vec3 a, vec3 b1, vec3 b2, vec2 b) {
  SST_PRECISE float b0 = 1.0f - b.x - b.y;
  SST_PRECISE vec3 r = b0 * a + b.x * b1 + b.y * b2;
  return r;
}

// The barycentrics b of point p in the plane of triangle (a, b1, b2): barycentric_mix3's inverse,
// by least squares (p off the plane is projected onto it). (0, 0) for a degenerate triangle.
SST_FUNC vec2 barycentric_of(vec3 a, vec3 b1, vec3 b2, vec3 p) {
  SST_PRECISE vec3 e1 = b1 - a;
  SST_PRECISE vec3 e2 = b2 - a;
  SST_PRECISE vec3 d = p - a;
  SST_PRECISE float d11 = dot3(e1, e1);
  SST_PRECISE float d12 = dot3(e1, e2);
  SST_PRECISE float d22 = dot3(e2, e2);
  SST_PRECISE float p1 = dot3(d, e1);
  SST_PRECISE float p2 = dot3(d, e2);
  SST_PRECISE float det = d11 * d22 - d12 * d12;
  if (!(abs(det) > 0.0f)) return vec2(0.0f);
  SST_PRECISE float u = (d22 * p1 - d12 * p2) / det;
  SST_PRECISE float v = (d11 * p2 - d12 * p1) / det;
  return vec2(u, v);
}

SST_FUNC vec2 barycentric_mix2(vec2 a, vec2 b1, vec2 b2, vec2 b) {
  SST_PRECISE float b0 = 1.0f - b.x - b.y;
  SST_PRECISE vec2 r = b0 * a + b.x * b1 + b.y * b2;
  return r;
}

SST_FUNC vec2 triangle_uv(SCENE_CTX_PARAM SST_IN(SceneTriangle) t, vec2 b) {
  return barycentric_mix2(SCENE_UV(t.v0), SCENE_UV(t.v1), SCENE_UV(t.v2), b);
}

SST_FUNC vec4 texture_or_one(SCENE_CTX_PARAM int texture, vec2 uv) {
  return texture >= 0 ? SCENE_TEXTURE_SAMPLE(texture, uv) : vec4(1.0f);
}

// Textures a, b, c and d at uv (texture_or_one each), sampled in one loop: a shader compiler
// inlines every call of the texture filter, so a surface's four textures sampled where they are
// used made four copies of it in every kernel that shades a hit (core/scene/texture_sample.h).
SST_FUNC void textures_at(SCENE_CTX_PARAM int a, int b, int c, int d, vec2 uv, SST_OUT(vec4) ta, SST_OUT(vec4) tb,
                          SST_OUT(vec4) tc, SST_OUT(vec4) td) {
  ta = vec4(1.0f);
  tb = vec4(1.0f);
  tc = vec4(1.0f);
  td = vec4(1.0f);
  for (uint k = 0u; k < 4u; ++k) {
    int texture = k == 0u ? a : (k == 1u ? b : (k == 2u ? c : d));
    if (texture < 0) continue;
    vec4 v = SCENE_TEXTURE_SAMPLE(texture, uv);
    if (k == 0u) ta = v;
    else if (k == 1u) tb = v;
    else if (k == 2u) tc = v;
    else td = v;
  }
}

// COLOR_0 at b. Equal corners (every scene without vertex colours) give that colour exactly, so
// that multiplying by it changes no bit.
SST_FUNC vec4 triangle_color(SCENE_CTX_PARAM SST_IN(SceneTriangle) t, vec2 b) {
  vec4 c0 = SCENE_COLOR(t.v0);
  vec4 c1 = SCENE_COLOR(t.v1);
  vec4 c2 = SCENE_COLOR(t.v2);
  if (c0 == c1 && c1 == c2) return c0;
  SST_PRECISE float b0 = 1.0f - b.x - b.y;
  SST_PRECISE vec4 r = b0 * c0 + b.x * c1 + b.y * c2;
  return r;
}

// Material m's alpha at a point whose COLOR_0 is `color` and whose base-colour texel is
// `base_texel` (vec4(1) without a texture): the factor times the texture's alpha times COLOR_0's.
SST_FUNC float surface_alpha_of(SST_IN(SceneMaterial) m, vec4 color, vec4 base_texel) {
  SST_PRECISE float a = m.alpha * color.w;
  if (m.base_color_texture >= 0) a = a * base_texel.w;
  return a;
}

// The same on triangle t at b.
SST_FUNC float surface_alpha(SCENE_CTX_PARAM SST_IN(SceneTriangle) t, SST_IN(SceneMaterial) m, vec2 b) {
  vec4 base_texel = texture_or_one(SCENE_CTX m.base_color_texture, triangle_uv(SCENE_CTX t, b));
  return surface_alpha_of(m, triangle_color(SCENE_CTX t, b), base_texel);
}

// Whether a hit on triangle tri at barycentrics b counts: the alpha test of glTF's MASK (and of
// BLEND, rendered as a cutout at 0.5) that every ray query applies, and that cuts emitters too.
SST_FUNC bool triangle_alpha_passes(SCENE_CTX_PARAM uint tri, vec2 b) {
  SceneTriangle t = SCENE_TRIANGLE(tri);
  SceneMaterial m = SCENE_MATERIAL(t.material);
  return m.alpha_cutoff <= 0.0f || surface_alpha(SCENE_CTX t, m, b) >= m.alpha_cutoff;
}

SST_END

#endif  // SST_CORE_SCENE_TRIANGLE_ATTRIBUTES_H
