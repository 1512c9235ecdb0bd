// The hooks of the shared scene kernels (core/scene/texture_sample.h,
// core/shading/surface_eval.h) bound to the scene buffers, and the kernels themselves:
// make_surface, triangle_emission, triangle_geometric_normal, triangle_area, texture_sample.
// The including shader declares the buffers first (core/scene/scene_layout.h), e.g.
//   #include "core/scene/scene_layout.h"
//   SCENE_BUFFERS(0)
//   #include "gpu/shaders/surface.glsl"
#ifndef SST_GPU_SHADERS_SURFACE_GLSL
#define SST_GPU_SHADERS_SURFACE_GLSL

#define TEXTURE_CTX_PARAM
#define TEXTURE_CTX
#define TEXTURE_WORD(t, w) scene_texels[(t).texel_offset + (w)]
#define TEXTURE_TABLE_WORD(i) scene_texels[i]
#include "core/scene/texture_sample.h"

#define SCENE_CTX_PARAM
#define SCENE_CTX
#define SCENE_TRIANGLE(t) scene_triangles[t]
#define SCENE_POSITION(i) scene_vertices[i].position
#define SCENE_NORMAL(i) scene_vertices[i].normal
#define SCENE_UV(i) vec2(scene_vertices[i].u, scene_vertices[i].v)
#define SCENE_TANGENT(i) scene_vertices[i].tangent
#define SCENE_COLOR(i) scene_vertices[i].color
#define SCENE_MATERIAL(m) scene_materials[m]
#define SCENE_TEXTURE_SAMPLE(k, uv) texture_sample(scene_textures[k], uv)
#include "core/shading/surface_eval.h"
// The alpha test of the BVH traversal (core/accel/bvh_traverse.h, included after this file).
#define BVH_ALPHA_TEST(triangle, b) triangle_alpha_passes(triangle, b)

#endif  // SST_GPU_SHADERS_SURFACE_GLSL
