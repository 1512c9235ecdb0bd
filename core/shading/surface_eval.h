// A ray's hit turned into what shading needs (position, normals facing the viewer, material values
// with textures applied, the radiance emitted toward the viewer), and the triangle quantities
// light sampling needs (geometric normal, area, emission), in the common subset of C++ and GLSL
// (core/math/cpu_gpu.h): core/shading/surface.h on the CPU, the shaders on the GPU.
//
// The scene is read through hooks the includer defines before including this file (the types
// are core/scene/scene_layout.h's):
//   SCENE_CTX_PARAM              a leading parameter with its trailing comma through which the
//                                hooks reach the scene (C++: `const ::sst::Scene& scene,`), empty
//                                in GLSL
//   SCENE_CTX                    the same as an argument
//   SCENE_TRIANGLE(t)            SceneTriangle: triangle t's vertex indices and material
//   SCENE_POSITION(i)            vec3: vertex i's position
//   SCENE_NORMAL(i)              vec3: vertex i's shading normal (unit, or zero)
//   SCENE_UV(i)                  vec2: vertex i's uv (zero when the scene has none)
//   SCENE_TANGENT(i)             vec4: vertex i's tangent and bitangent sign (zero when it has none)
//   SCENE_COLOR(i)               vec4: vertex i's COLOR_0 (1 when it has none)
//   SCENE_MATERIAL(m)            SceneMaterial: material m, its texture indices >= 0 only for
//                                textures that exist
//   SCENE_TEXTURE_SAMPLE(k, uv)  vec4: texture k (>= 0) at uv (core/scene/texture_sample.h)
//
// Every expression keeps glm's operation order (dot, cross, mix written out in
// core/math/vector_math.h) and its bits are fixed by SST_PRECISE, so that both backends compute
// the same floats up to the GPU's sqrt and division.
#ifndef SST_CORE_SHADING_SURFACE_EVAL_H
#define SST_CORE_SHADING_SURFACE_EVAL_H
#include "core/accel/ray_offset.h"
#include "core/math/vector_math.h"
#include "core/scene/scene_layout.h"
#include "core/scene/triangle_attributes.h"

#if !defined(SCENE_CTX_PARAM) || !defined(SCENE_CTX) || !defined(SCENE_TRIANGLE) || !defined(SCENE_POSITION) || \
    !defined(SCENE_NORMAL) || !defined(SCENE_UV) || !defined(SCENE_TANGENT) || !defined(SCENE_COLOR) ||   \
    !defined(SCENE_MATERIAL) || !defined(SCENE_TEXTURE_SAMPLE)
#error "define the SCENE_* hooks before including core/shading/surface_eval.h"
#endif

SST_BEGIN

// `incoming` of make_surface is the direction of the ray that hit the surface.
struct Surface {
  vec3 p SST_DEFAULT(vec3(0.0f));
  vec3 ng SST_DEFAULT(vec3(0.0f));  // geometric normal, flipped to the side the ray came from
  vec3 ns SST_DEFAULT(vec3(0.0f));  // interpolated shading normal, on the same side as ng
  vec2 uv SST_DEFAULT(vec2(0.0f));
  uint triangle SST_DEFAULT(0u);
  uint material SST_DEFAULT(0u);
  bool front_face SST_DEFAULT(true);  // the ray hit the side the triangle's winding faces
  vec3 base_color SST_DEFAULT(vec3(1.0f));
  float metallic SST_DEFAULT(0.0f);
  float roughness SST_DEFAULT(1.0f);
  vec3 emission SST_DEFAULT(vec3(0.0f));  // radiance leaving toward the viewer (0 from the back of one-sided)
  float offset SST_DEFAULT(0.0f);  // how far rays leaving p are lifted along ng (core/accel/ray_offset.h)
  // From p to the smooth surface the vertex normals describe (terminator_lift): where shadow rays
  // leave near the shadow terminator; zero on flat-shaded triangles.
  vec3 lift SST_DEFAULT(vec3(0.0f));
};

// Hanika's shadow-terminator lift ("Hacking the Shadow Terminator", Ray Tracing Gems II, 2021):
// p (barycentrics b of triangle v0 v1 v2) moved onto each vertex's tangent plane that it lies
// under, the three moves blended by b. A coarse mesh's facet lies under the curved surface its
// vertex normals describe, so a shadow ray from the facet can be blocked by the neighbouring facet
// where the smooth surface sees the light; from the lifted point it is not. n0..n2 are the vertex
// normals on the side the ray came from.
SST_FUNC vec3 terminator_lift(vec3 v0, vec3 v1, vec3 v2, vec3 n0, vec3 n1, vec3 n2, vec3 p, vec2 b) {
  SST_PRECISE float d0 = min(dot3(p - v0, n0), 0.0f) * (1.0f - b.x - b.y);
  SST_PRECISE float d1 = min(dot3(p - v1, n1), 0.0f) * b.x;
  SST_PRECISE float d2 = min(dot3(p - v2, n2), 0.0f) * b.y;
  SST_PRECISE vec3 lift = -(n0 * d0 + n1 * d1 + n2 * d2);
  return lift;
}

// The unit shading normal n bent by material m's tangent-space normal map, whose texel at the
// point is `texel` (sampled by the caller, textures_at). The tangent is
// the vertices' TANGENT interpolated, or, where they have none, the triangle's dp/du (per
// triangle, unlike MikkTSpace's per-vertex average: the same on planar mappings, faceted on
// curved ones), made orthogonal to n; the bitangent is cross(n, tangent) * w, w the TANGENT's
// sign or, derived, the sign that makes it -dp/dv (glTF's v runs down the image, a normal map's
// +y up it). n is returned unbent where no frame exists (no uv parametrisation) or where the
// bent normal would cross the geometric normal ng's plane, which shading cannot take.
SST_FUNC vec3 normal_mapped(SCENE_CTX_PARAM SST_IN(SceneTriangle) t, SST_IN(SceneMaterial) m, vec2 b, vec4 texel,
                            vec3 n, vec3 ng) {
  vec4 t0 = SCENE_TANGENT(t.v0);
  vec4 t1 = SCENE_TANGENT(t.v1);
  vec4 t2 = SCENE_TANGENT(t.v2);
  SST_PRECISE float b0 = 1.0f - b.x - b.y;
  SST_PRECISE vec3 tangent = b0 * vec3(t0.x, t0.y, t0.z) + b.x * vec3(t1.x, t1.y, t1.z) + b.y * vec3(t2.x, t2.y, t2.z);
  float w = t0.w < 0.0f ? -1.0f : 1.0f;
  if (dot3(tangent, tangent) == 0.0f) {
    vec3 p0 = SCENE_POSITION(t.v0);
    vec2 uv0 = SCENE_UV(t.v0);
    SST_PRECISE vec3 dp1 = SCENE_POSITION(t.v1) - p0;
    SST_PRECISE vec3 dp2 = SCENE_POSITION(t.v2) - p0;
    SST_PRECISE vec2 duv1 = SCENE_UV(t.v1) - uv0;
    SST_PRECISE vec2 duv2 = SCENE_UV(t.v2) - uv0;
    SST_PRECISE float det = duv1.x * duv2.y - duv1.y * duv2.x;
    if (det == 0.0f) return n;
    SST_PRECISE vec3 dpdu = (dp1 * duv2.y - dp2 * duv1.y) / det;
    SST_PRECISE vec3 dpdv = (dp2 * duv1.x - dp1 * duv2.x) / det;
    tangent = dpdu;
    w = dot3(cross3(n, dpdu), dpdv) > 0.0f ? -1.0f : 1.0f;
  }
  SST_PRECISE vec3 tp = tangent - n * dot3(n, tangent);
  float tl = length3(tp);
  if (!(tl > 0.0f) || !is_finite(tl)) return n;
  SST_PRECISE vec3 tu = tp / tl;
  SST_PRECISE vec3 bt = cross3(n, tu) * w;
  SST_PRECISE float lx = (texel.x * 2.0f - 1.0f) * m.normal_scale;
  SST_PRECISE float ly = (texel.y * 2.0f - 1.0f) * m.normal_scale;
  SST_PRECISE float lz = texel.z * 2.0f - 1.0f;
  SST_PRECISE vec3 bent = tu * lx + bt * ly + n * lz;
  float bl = length3(bent);
  if (!(bl > 0.0f) || !is_finite(bl)) return n;
  SST_PRECISE vec3 r = bent / bl;
  if (dot3(r, ng) * dot3(n, ng) <= 0.0f) return n;
  return r;
}

// Unit, by winding; +z for a degenerate triangle.
SST_FUNC vec3 triangle_geometric_normal(SCENE_CTX_PARAM uint tri) {
  SceneTriangle t = SCENE_TRIANGLE(tri);
  vec3 p0 = SCENE_POSITION(t.v0);
  SST_PRECISE vec3 e1 = SCENE_POSITION(t.v1) - p0;
  SST_PRECISE vec3 e2 = SCENE_POSITION(t.v2) - p0;
  vec3 n = cross3(e1, e2);
  float len = length3(n);
  return len > 0.0f ? n / len : vec3(0.0f, 0.0f, 1.0f);
}

SST_FUNC float triangle_area(SCENE_CTX_PARAM uint tri) {
  SceneTriangle t = SCENE_TRIANGLE(tri);
  vec3 p0 = SCENE_POSITION(t.v0);
  SST_PRECISE vec3 e1 = SCENE_POSITION(t.v1) - p0;
  SST_PRECISE vec3 e2 = SCENE_POSITION(t.v2) - p0;
  SST_PRECISE float a = 0.5f * length3(cross3(e1, e2));
  return a;
}

// Emitted radiance of triangle `tri` at barycentrics (b1, b2), seen from the side `front_face`.
// Material m's emitted radiance, seen from the side `front_face`, at a point of alpha `alpha` where
// its emissive texture reads `emissive_texel`.
SST_FUNC vec3 material_emission(SST_IN(SceneMaterial) m, bool front_face, float alpha, vec4 emissive_texel) {
  if (!front_face && m.double_sided == 0u) return vec3(0.0f);
  if (m.alpha_cutoff > 0.0f && alpha < m.alpha_cutoff) return vec3(0.0f);
  if (m.emissive_texture < 0) return m.emission;
  SST_PRECISE vec3 e = m.emission * vec3(emissive_texel.x, emissive_texel.y, emissive_texel.z);
  return e;
}

// Emitted radiance of triangle `tri` at barycentrics (b1, b2), seen from the side `front_face`.
SST_FUNC vec3 triangle_emission(SCENE_CTX_PARAM uint tri, vec2 barycentric, bool front_face) {
  SceneTriangle t = SCENE_TRIANGLE(tri);
  SceneMaterial m = SCENE_MATERIAL(t.material);
  if (!front_face && m.double_sided == 0u) return vec3(0.0f);
  if (m.alpha_cutoff <= 0.0f && m.emissive_texture < 0) return m.emission;
  vec4 base_texel, emissive_texel, unused0, unused1;
  textures_at(SCENE_CTX m.alpha_cutoff > 0.0f ? m.base_color_texture : -1, m.emissive_texture, -1, -1,
              triangle_uv(SCENE_CTX t, barycentric), base_texel, emissive_texel, unused0, unused1);
  float alpha = surface_alpha_of(m, triangle_color(SCENE_CTX t, barycentric), base_texel);
  return material_emission(m, front_face, alpha, emissive_texel);
}

// The surface that a ray with direction `incoming` hits on triangle `tri` at Embree's
// barycentrics b.
SST_FUNC Surface make_surface(SCENE_CTX_PARAM uint tri, vec2 b, vec3 incoming) {
  Surface s;
  SceneTriangle t = SCENE_TRIANGLE(tri);
  // Recompute the point from the triangle rather than origin + t*dir: it is exact on the surface.
  vec3 v0 = SCENE_POSITION(t.v0);
  vec3 v1 = SCENE_POSITION(t.v1);
  vec3 v2 = SCENE_POSITION(t.v2);
  s.p = barycentric_mix3(v0, v1, v2, b);
  s.triangle = tri;
  s.material = t.material;
  s.ng = triangle_geometric_normal(SCENE_CTX tri);
  s.offset = triangle_point_offset(v0, v1, v2, s.p, s.ng);
  s.front_face = dot3(s.ng, incoming) < 0.0f;
  if (!s.front_face) s.ng = -s.ng;
  s.uv = triangle_uv(SCENE_CTX t, b);
  SceneMaterial m = SCENE_MATERIAL(s.material);
  vec3 n0 = SCENE_NORMAL(t.v0), n1 = SCENE_NORMAL(t.v1), n2 = SCENE_NORMAL(t.v2);
  vec3 ns = barycentric_mix3(n0, n1, n2, b);
  // The vertex normals on the viewer's side, as ns is turned below.
  float side = dot3(ns, s.ng) < 0.0f ? -1.0f : 1.0f;
  s.lift = terminator_lift(v0, v1, v2, n0 * side, n1 * side, n2 * side, s.p, b);
  float len = length3(ns);
  ns = len > 0.0f && is_finite(len) ? ns / len : s.ng;
  vec4 normal_texel, base_texel, mr, emissive_texel;
  textures_at(SCENE_CTX m.normal_texture, m.base_color_texture, m.metallic_roughness_texture, m.emissive_texture, s.uv,
              normal_texel, base_texel, mr, emissive_texel);
  if (m.normal_texture >= 0) ns = normal_mapped(SCENE_CTX t, m, b, normal_texel, ns, s.ng);
  // Shading normals are interpolated per vertex and may point away from the viewer's side;
  // keep them in the hemisphere of the geometric normal so shading never sees a back face.
  if (dot3(ns, s.ng) < 0.0f) ns = -ns;
  s.ns = ns;

  vec4 color = triangle_color(SCENE_CTX t, b);
  SST_PRECISE vec3 base = m.base_color * vec3(base_texel.x, base_texel.y, base_texel.z) * vec3(color.x, color.y, color.z);
  s.base_color = base;
  SST_PRECISE float metallic = m.metallic * mr.z;
  SST_PRECISE float roughness = m.roughness * mr.y;
  s.metallic = metallic;
  s.roughness = roughness;
  s.emission = material_emission(m, s.front_face, surface_alpha_of(m, color, base_texel), emissive_texel);
  return s;
}

SST_END

#endif  // SST_CORE_SHADING_SURFACE_EVAL_H
