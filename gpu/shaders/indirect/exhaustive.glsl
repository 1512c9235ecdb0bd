// The GLSL twin of core/manylight/exhaustive_sampler.cpp: `exhaustive`, every VPL with its
// shadow ray, summed in VPL order as on the CPU.
#ifndef SST_GPU_SHADERS_INDIRECT_EXHAUSTIVE_GLSL
#define SST_GPU_SHADERS_INDIRECT_EXHAUSTIVE_GLSL

IndirectEstimate estimate_exhaustive(ShadingPoint sp) {
  IndirectEstimate e = indirect_estimate_zero();
  for (uint j = 0u; j < ml_params.vpl_count; ++j) {
    BVH_COUNT_ITERATION();
    vec3 c = shade_vpl(sp, ml_vpl(j), e.shadow_rays);
    e.value += c;
  }
  return e;
}

#endif
