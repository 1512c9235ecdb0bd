// The GLSL twin of core/manylight/uniform_sampler.cpp: `uniform`, one VPL drawn uniformly,
// weighted by the VPL count.
#ifndef SST_GPU_SHADERS_INDIRECT_UNIFORM_GLSL
#define SST_GPU_SHADERS_INDIRECT_UNIFORM_GLSL

IndirectEstimate estimate_uniform(ShadingPoint sp, inout PixelSampler ps) {
  IndirectEstimate e = indirect_estimate_zero();
  uint n = ml_params.vpl_count;
  if (n == 0u) return e;
  precise float scaled = pixel_sampler_get1d(ps) * float(n);
  uint j = min(n - 1u, uint(scaled));
  vec3 c = shade_vpl(sp, ml_vpl(j), e.shadow_rays);
  precise vec3 v = c * float(n);
  e.value = v;
  return e;
}

#endif
