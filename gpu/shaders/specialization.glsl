// Specialization constants: values a pipeline fixes when it is created (ComputePipeline's
// `specialization`, indexed by the ids of gpu/shaders/specialization_ids.h), so that the driver
// compiles only the branches they select. All shaders are inlined whole, so one kernel holding every light
// sampler and every many-light method took Mesa 25's lavapipe minutes to compile, and on a GPU
// costs registers for code that never runs. kSpecUnset (the default) leaves the choice to the
// run-time value, as tests that switch samplers between dispatches need.
#ifndef SST_GPU_SHADERS_SPECIALIZATION_GLSL
#define SST_GPU_SHADERS_SPECIALIZATION_GLSL

#include "gpu/shaders/specialization_ids.h"
#define kSpecUnset SST_SPEC_UNSET
layout(constant_id = SST_SPEC_LIGHT_SAMPLER) const uint kSpecLightSampler = kSpecUnset;
layout(constant_id = SST_SPEC_MANY_LIGHT_METHOD) const uint kSpecManyLightMethod = kSpecUnset;
layout(constant_id = SST_SPEC_OWN_DIRECT) const uint kSpecOwnDirect = kSpecUnset;

#define LIGHT_SAMPLER_KIND (kSpecLightSampler != kSpecUnset ? kSpecLightSampler : LIGHT_HEADER.sampler_kind)

#endif  // SST_GPU_SHADERS_SPECIALIZATION_GLSL
