// Specialization constants: values a pipeline fixes when it is created (ComputePipeline's
// `specialization`, indexed by constant_id, gpu/compute_pipeline.h), so that the driver compiles
// only the branches they select. All shaders are inlined whole, so one kernel holding every light
// sampler and every many-light method took Mesa 25's lavapipe minutes to compile, and on a GPU
// costs registers for code that never runs. kSpecUnset (the default) leaves the choice to the
// run-time value, as tests that switch samplers between dispatches need.
#ifndef SST_GPU_SHADERS_SPECIALIZATION_GLSL
#define SST_GPU_SHADERS_SPECIALIZATION_GLSL

#define kSpecUnset 0xFFFFFFFFu
// LIGHT_SAMPLER_*: the light sampler (core/lights/light_sample.h's LIGHT_SAMPLER_KIND hook).
layout(constant_id = 0) const uint kSpecLightSampler = kSpecUnset;
// ML_METHOD_* ids (core/manylight/many_light_methods.h): the indirect estimate of many_light.comp.
layout(constant_id = 1) const uint kSpecManyLightMethod = kSpecUnset;
// 0 or 1: whether many_light.comp's direct light comes from rtslc's cuts
// (SamplerParams.rtslc_direct_cut_max_size != 0).
layout(constant_id = 2) const uint kSpecOwnDirect = kSpecUnset;

#define LIGHT_SAMPLER_KIND (kSpecLightSampler != kSpecUnset ? kSpecLightSampler : LIGHT_HEADER.sampler_kind)

#endif  // SST_GPU_SHADERS_SPECIALIZATION_GLSL
