// The hooks of the shared light sampling (core/lights/light_sample.h) bound to the light buffers,
// and the sampling itself: light_sample, light_pdf_emissive_hit, light_sample_emission,
// light_pick, light_pick_for, light_pick_pmf. The including shader declares the scene and light buffers first, e.g.
//   #include "core/scene/scene_layout.h"
//   #include "core/lights/light_layout.h"
//   SCENE_BUFFERS(0)
//   LIGHT_BUFFERS(5)
//   #include "gpu/shaders/light_sampler.glsl"
#ifndef SST_GPU_SHADERS_LIGHT_SAMPLER_GLSL
#define SST_GPU_SHADERS_LIGHT_SAMPLER_GLSL
#include "gpu/shaders/specialization.glsl"
#include "gpu/shaders/surface.glsl"

#define LIGHT_CTX_PARAM
#define LIGHT_CTX
#define LIGHT_HEADER light_header
#define LIGHT_PUNCTUAL(i) light_punctual[i]
#define LIGHT_CDF(i) light_distribution[i]
#define LIGHT_EMISSIVE(k) light_emissive[k]
#define LIGHT_OF_TRIANGLE(t) light_of_triangle[t]
#define LIGHT_TREE(i) light_tree[i]
#include "core/lights/light_sample.h"

#endif  // SST_GPU_SHADERS_LIGHT_SAMPLER_GLSL
