// The path tracer's path (core/pt/trace_path.h) on the GPU, over the scene and light buffers and
// the flat BVH (gpu/shaders/ray_queries.glsl). The including shader declares, before including
// this file: the scene buffers (SCENE_BUFFERS(first), core/scene/scene_layout.h), the light
// buffers (LIGHT_BUFFERS(first), core/lights/light_layout.h), and what ray_queries.glsl needs.
#ifndef SST_GPU_SHADERS_PATH_TRACE_GLSL
#define SST_GPU_SHADERS_PATH_TRACE_GLSL
#include "gpu/shaders/light_sampler.glsl"
#include "gpu/shaders/ray_queries.glsl"
#include "core/pt/trace_path.h"

#endif  // SST_GPU_SHADERS_PATH_TRACE_GLSL
