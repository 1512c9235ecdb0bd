// A ray's hit turned into what shading needs, on the GPU: the GLSL twin of
// core/shading/surface.cpp (make_surface, triangle_emission, triangle_geometric_normal,
// triangle_area) and of core/scene/texture.cpp (Texture::sample, Texture::texel).
//
// The including shader declares, before including this file, the scene buffers of
// core/scene/scene_layout.h under these names (SCENE_BUFFERS(first_binding) does it):
//   SceneVertex   scene_vertices[]
//   SceneTriangle scene_triangles[]
//   SceneMaterial scene_materials[]
//   SceneTexture  scene_textures[]
//   uint          scene_texels[]
// e.g.
//   #include "core/scene/scene_layout.h"
//   SCENE_BUFFERS(0)
//   #include "gpu/shaders/surface.glsl"
//
// Same bits as the CPU: every expression keeps the C++ (glm) operation order, and the results are
// `precise`, so that no a * b + c is fused into an fma (the C++ is built for baseline x86-64,
// without fma). glm's dot(a, b) is (a.x * b.x + a.y * b.y) + a.z * b.z, its cross the textbook
// one, its mix(x, y, a) x * (1 - a) + y * a: written out here rather than calling the GLSL
// built-ins, whose evaluation order is the driver's. 8-bit texels decode through the tables of
// scene_layout.h (at the start of scene_texels[]). What may still differ: sqrt and division, which Vulkan does not require to be
// correctly rounded (a few ulps in normalised normals, never in positions, uvs or texels).
#ifndef SST_GPU_SHADERS_SURFACE_GLSL
#define SST_GPU_SHADERS_SURFACE_GLSL
#include "core/math/vector_math.h"

// sst::Surface. `incoming` of make_surface is the direction of the ray that hit the surface.
struct Surface {
  vec3 p;
  vec3 ng;          // geometric normal, flipped to the side the ray came from
  vec3 ns;          // interpolated shading normal, on the same side as ng
  vec2 uv;
  uint triangle;
  uint material;
  bool front_face;  // the ray hit the side the triangle's winding faces
  vec3 base_color;
  float metallic;
  float roughness;
  vec3 emission;    // radiance leaving toward the viewer (0 from the back of one-sided)
};

// ---- float helpers in glm's operation order --------------------------------------------------

// (1 - b.x - b.y) * a + b.x * b1 + b.y * c, as the C++ writes its interpolations.
vec3 scene_interpolate3(vec3 a, vec3 b1v, vec3 c, vec2 b) {
  precise float b0 = 1.0 - b.x - b.y;
  precise vec3 r = b0 * a + b.x * b1v + b.y * c;
  return r;
}

vec2 scene_interpolate2(vec2 a, vec2 b1v, vec2 c, vec2 b) {
  precise float b0 = 1.0 - b.x - b.y;
  precise vec2 r = b0 * a + b.x * b1v + b.y * c;
  return r;
}

vec4 scene_mix4(vec4 x, vec4 y, float a) {
  precise vec4 r = x * (1.0 - a) + y * a;
  return r;
}

// ---- textures (core/scene/texture.cpp) ----------------------------------------------------------

// Texture::texel: linear RGBA of texel i (i counts texels, row-major).
vec4 scene_texel(SceneTexture t, uint i) {
  if (t.format == SCENE_TEXTURE_RGBA32F) {
    uint o = t.texel_offset + 4u * i;
    return vec4(uintBitsToFloat(scene_texels[o]), uintBitsToFloat(scene_texels[o + 1u]),
                uintBitsToFloat(scene_texels[o + 2u]), uintBitsToFloat(scene_texels[o + 3u]));
  }
  uint v = scene_texels[t.texel_offset + i];
  float a = uintBitsToFloat(scene_texels[SCENE_TEXELS_UNORM8_TABLE + (v >> 24)]);
  if (t.format == SCENE_TEXTURE_RGBA8_SRGB)
    return vec4(uintBitsToFloat(scene_texels[SCENE_TEXELS_SRGB_TABLE + (v & 0xFFu)]),
                uintBitsToFloat(scene_texels[SCENE_TEXELS_SRGB_TABLE + ((v >> 8) & 0xFFu)]),
                uintBitsToFloat(scene_texels[SCENE_TEXELS_SRGB_TABLE + ((v >> 16) & 0xFFu)]), a);
  precise float inv = uintBitsToFloat(SCENE_INV_255_BITS);
  precise vec3 c = vec3(float(v & 0xFFu) * inv, float((v >> 8) & 0xFFu) * inv, float((v >> 16) & 0xFFu) * inv);
  return vec4(c, a);
}

// i mod n in [0, n) for n > 0 and any i (GLSL's % is undefined for negative operands).
int scene_floor_mod(int i, int n) { return i >= 0 ? i % n : (n - 1) - ((-1 - i) % n); }

// wrap_index: a texel coordinate wrapped into [0, n).
int scene_wrap_index(int i, int n, uint mode) {
  if (mode == SCENE_WRAP_CLAMP_TO_EDGE) return clamp(i, 0, n - 1);
  if (mode == SCENE_WRAP_MIRRORED_REPEAT) {
    int period = 2 * n;
    int m = scene_floor_mod(i, period);
    return m < n ? m : period - 1 - m;
  }
  if (i < 0) i += n;
  if (i >= n) i -= n;
  return (i >= 0 && i < n) ? i : scene_floor_mod(i, n);
}

// reduce: a repeating coordinate brought into [0, 1) first.
float scene_wrap_reduce(float u, uint mode) {
  precise float r = u - floor(u);
  return mode == SCENE_WRAP_REPEAT ? r : u;
}

// Texture::sample of scene_textures[index] (index >= 0).
vec4 scene_texture_sample(int index, vec2 uv) {
  SceneTexture t = scene_textures[index];
  int w = t.width, h = t.height;
  if (w <= 0 || h <= 0) return vec4(1.0);
  if (!is_finite(uv.x) || !is_finite(uv.y)) return scene_texel(t, 0u);
  // Texel centres sit at half-integers.
  precise float x = scene_wrap_reduce(uv.x, t.wrap_s) * float(w) - 0.5;
  precise float y = scene_wrap_reduce(uv.y, t.wrap_t) * float(h) - 0.5;
  x = clamp(x, -float(w) * 1024.0, float(w) * 1024.0);  // keep int conversion exact
  y = clamp(y, -float(h) * 1024.0, float(h) * 1024.0);
  if (t.nearest != 0u) {
    precise float xn = x + 0.5, yn = y + 0.5;
    int ix = scene_wrap_index(int(floor(xn)), w, t.wrap_s);
    int iy = scene_wrap_index(int(floor(yn)), h, t.wrap_t);
    return scene_texel(t, uint(iy) * uint(w) + uint(ix));
  }
  float fx = floor(x), fy = floor(y);
  precise float tx = x - fx, ty = y - fy;
  int x0 = scene_wrap_index(int(fx), w, t.wrap_s), x1 = scene_wrap_index(int(fx) + 1, w, t.wrap_s);
  int y0 = scene_wrap_index(int(fy), h, t.wrap_t), y1 = scene_wrap_index(int(fy) + 1, h, t.wrap_t);
  uint r0 = uint(y0) * uint(w), r1 = uint(y1) * uint(w);
  return scene_mix4(scene_mix4(scene_texel(t, r0 + uint(x0)), scene_texel(t, r0 + uint(x1)), tx),
                    scene_mix4(scene_texel(t, r1 + uint(x0)), scene_texel(t, r1 + uint(x1)), tx), ty);
}

vec4 scene_texture_or_one(int index, vec2 uv) {
  return index >= 0 ? scene_texture_sample(index, uv) : vec4(1.0);
}

// ---- surfaces (core/shading/surface.cpp) ---------------------------------------------------------

vec2 scene_interpolate_uv(SceneTriangle t, vec2 b) {
  SceneVertex a = scene_vertices[t.v0], b1v = scene_vertices[t.v1], c = scene_vertices[t.v2];
  return scene_interpolate2(vec2(a.u, a.v), vec2(b1v.u, b1v.v), vec2(c.u, c.v), b);
}

// Unit, by winding; +z for a degenerate triangle.
vec3 triangle_geometric_normal(uint tri) {
  SceneTriangle t = scene_triangles[tri];
  vec3 p0 = scene_vertices[t.v0].position;
  precise vec3 e1 = scene_vertices[t.v1].position - p0;
  precise vec3 e2 = scene_vertices[t.v2].position - p0;
  vec3 n = cross3(e1, e2);
  float len = length3(n);
  return len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
}

float triangle_area(uint tri) {
  SceneTriangle t = scene_triangles[tri];
  vec3 p0 = scene_vertices[t.v0].position;
  precise vec3 e1 = scene_vertices[t.v1].position - p0;
  precise vec3 e2 = scene_vertices[t.v2].position - p0;
  precise float a = 0.5 * length3(cross3(e1, e2));
  return a;
}

// Emitted radiance of triangle `tri` at barycentrics (b1, b2), seen from the side `front_face`.
vec3 triangle_emission(uint tri, vec2 barycentric, bool front_face) {
  SceneTriangle t = scene_triangles[tri];
  SceneMaterial m = scene_materials[t.material];
  if (!front_face && m.double_sided == 0u) return vec3(0.0);
  if (m.emissive_texture < 0) return m.emission;
  vec2 uv = scene_interpolate_uv(t, barycentric);
  precise vec3 e = m.emission * scene_texture_or_one(m.emissive_texture, uv).xyz;
  return e;
}

// `incoming` is the ray direction that hit the surface; (b.x, b.y) Embree's barycentrics.
Surface make_surface(uint tri, vec2 b, vec3 incoming) {
  Surface s;
  SceneTriangle t = scene_triangles[tri];
  SceneVertex v0 = scene_vertices[t.v0], v1 = scene_vertices[t.v1], v2 = scene_vertices[t.v2];
  // Recompute the point from the triangle rather than origin + t*dir: it is exact on the surface.
  s.p = scene_interpolate3(v0.position, v1.position, v2.position, b);
  s.triangle = tri;
  s.material = t.material;
  s.ng = triangle_geometric_normal(tri);
  s.front_face = dot3(s.ng, incoming) < 0.0;
  if (!s.front_face) s.ng = -s.ng;
  vec3 ns = scene_interpolate3(v0.normal, v1.normal, v2.normal, b);
  float len = length3(ns);
  ns = len > 0.0 && is_finite(len) ? ns / len : s.ng;
  // Shading normals are interpolated per vertex and may point away from the viewer's side;
  // keep them in the hemisphere of the geometric normal so shading never sees a back face.
  if (dot3(ns, s.ng) < 0.0) ns = -ns;
  s.ns = ns;
  s.uv = scene_interpolate2(vec2(v0.u, v0.v), vec2(v1.u, v1.v), vec2(v2.u, v2.v), b);

  SceneMaterial m = scene_materials[s.material];
  precise vec3 base = m.base_color * scene_texture_or_one(m.base_color_texture, s.uv).xyz;
  s.base_color = base;
  vec4 mr = scene_texture_or_one(m.metallic_roughness_texture, s.uv);
  precise float metallic = m.metallic * mr.z, roughness = m.roughness * mr.y;
  s.metallic = metallic;
  s.roughness = roughness;
  s.emission = triangle_emission(tri, b, s.front_face);
  return s;
}

#endif  // SST_GPU_SHADERS_SURFACE_GLSL
