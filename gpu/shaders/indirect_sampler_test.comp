#version 450
#extension GL_GOOGLE_include_directive : require
// Runs estimate_indirect (gpu/shaders/indirect_sampler.glsl) at shading points the CPU computed,
// for tests/gpu/indirect_sampler_gpu_test.cpp: one invocation per point, the pixel sampler
// continued from the CPU's state (seed, pixel, sample index, sets already drawn), the estimate
// and the sets drawn after it written out.
// Bindings: 0..6 the many-light inputs (MANY_LIGHT_BUFFERS), 7 BVH nodes, 8 BVH triangles,
// 9 IndirectTestPoint points[], 10 IndirectTestResult results[].
#include "core/manylight/many_light_layout.h"
#include "core/accel/bvh_layout.h"

// A shading point with its pixel sampler's state (C++ twin in the test).
struct IndirectTestPoint {
  vec3 p;
  uint seed;
  vec3 ng;
  uint pixel;
  vec3 t;
  uint sample_index;
  vec3 b;
  uint sets_used;  // PixelSampler::sets_used() when the CPU called estimate()
  vec3 n;
  int x;
  vec3 wo;
  int y;
  vec3 diffuse;
  float alpha;
  vec3 f0;
  uint specular;
  float depth;
  uint pad0;
  uint pad1;
  uint pad2;
};

struct IndirectTestResult {
  vec3 value;
  uint nodes_visited;
  uint shadow_rays;
  uint sets_used;  // after estimate()
  uint pad0;
  uint pad1;
};

MANY_LIGHT_BUFFERS(0)
layout(std430, binding = 7) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 8) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };
layout(std430, binding = 9) readonly buffer Points { IndirectTestPoint points[]; };
layout(std430, binding = 10) writeonly buffer Results { IndirectTestResult results[]; };
layout(push_constant) uniform Push {
  uint count;
  float ray_epsilon;
} push;

#define BVH_NODE(i) bvh_nodes[i]
#define BVH_TRIANGLE(i) bvh_triangles[i]
#include "core/accel/bvh_traverse.h"
#define SCENE_RAY_EPSILON push.ray_epsilon
#include "gpu/shaders/indirect_sampler.glsl"

layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  IndirectTestPoint q = points[i];
  ShadingPoint sp;
  sp.p = q.p;
  sp.ng = q.ng;
  sp.offset = SCENE_RAY_EPSILON;
  sp.lift = vec3(0.0);
  sp.basis.t = q.t;
  sp.basis.b = q.b;
  sp.basis.n = q.n;
  sp.wo = q.wo;
  sp.brdf.diffuse = q.diffuse;
  sp.brdf.f0 = q.f0;
  sp.brdf.alpha = q.alpha;
  sp.brdf.specular = q.specular != 0u;
  sp.x = q.x;
  sp.y = q.y;
  sp.depth = q.depth;
  PixelSampler ps = pixel_sampler(q.seed, q.pixel, q.sample_index);
  ps.sets_used = q.sets_used;  // get2d only counts sets: the CPU's draws so far
  IndirectEstimate e = estimate_indirect(sp, ps);
  IndirectTestResult r;
  r.value = e.value;
  r.nodes_visited = e.nodes_visited;
  r.shadow_rays = e.shadow_rays;
  r.sets_used = ps.sets_used;
  r.pad0 = 0u;
  r.pad1 = 0u;
  results[i] = r;
}
