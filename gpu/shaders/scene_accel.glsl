// The scene's ray-tracing structure at bindings 5 and 6, which every rendering shader declares by
// including this file after the BVH layout (core/accel/bvh_layout.h): the flat BVH's nodes (5)
// and triangles (6), which the shared traversal (core/accel/bvh_traverse.h) reads, or, in the
// shaders' ray-query builds (SST_RAY_QUERY, gpu/CMakeLists.txt), the scene's top-level
// acceleration structure at 5 (gpu/acceleration_structure.h), traced by gpu/shaders/ray_queries.glsl.
// The traversal then stays declared but unused, its arrays aliasing binding 6.
#ifndef SST_GPU_SHADERS_SCENE_ACCEL_GLSL
#define SST_GPU_SHADERS_SCENE_ACCEL_GLSL

#if SST_RAY_QUERY
#extension GL_EXT_ray_query : require
layout(binding = 5) uniform accelerationStructureEXT scene_top_level;
layout(std430, binding = 6) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 6) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };
#else
layout(std430, binding = 5) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 6) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };
#endif
#define BVH_NODE(i) bvh_nodes[i]
#define BVH_TRIANGLE(i) bvh_triangles[i]

#endif  // SST_GPU_SHADERS_SCENE_ACCEL_GLSL
