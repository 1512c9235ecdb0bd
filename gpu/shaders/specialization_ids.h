// The ids of the shaders' specialization constants (gpu/shaders/specialization.glsl), shared by
// the GLSL that declares them and the C++ that fixes them (ComputePipeline's `specialization`, a
// value per id in this order).
#ifndef SST_GPU_SHADERS_SPECIALIZATION_IDS_H
#define SST_GPU_SHADERS_SPECIALIZATION_IDS_H

#define SST_SPEC_LIGHT_SAMPLER 0      // LIGHT_SAMPLER_*: the light sampler
#define SST_SPEC_MANY_LIGHT_METHOD 1  // ML_METHOD_* id: many_light.comp's indirect estimate
#define SST_SPEC_OWN_DIRECT 2         // 0 or 1: many_light.comp's direct light from rtslc's cuts
#define SST_SPEC_COUNT 3
#define SST_SPEC_UNSET 0xFFFFFFFFu    // the constant's default: the run-time value decides

#endif  // SST_GPU_SHADERS_SPECIALIZATION_IDS_H
