// The list of VPL methods (shared C++/GLSL source): one line each, `X(name, id)`, where name is the
// method's folder core/manylight/<name>/ and what sst-render's --method takes, and id its
// SamplerParams.method on the GPU (unique, never reused). Everything that names every VPL method
// is generated from this list:
//   ML_METHOD_<name>                        the ids (many_light_layout.h)
//   the estimate switch                     estimate_indirect (gpu/shaders/indirect_sampler.glsl)
//   the registry entries                    <name>_method_info(), core/pipeline/method_registry.cpp
//   the test case lists                     tests/core/manylight/extremes_test.cpp, tests/gpu/
// docs/design/adding-a-method.md has the steps for a new one.
#ifndef SST_CORE_MANYLIGHT_MANY_LIGHT_METHODS_H
#define SST_CORE_MANYLIGHT_MANY_LIGHT_METHODS_H

#define SST_MANY_LIGHT_METHODS(X) \
  X(exhaustive, 0u)               \
  X(uniform, 1u)                  \
  X(slc, 2u)                      \
  X(sst, 3u)                      \
  X(rtslc, 4u)                    \
  X(hybrid, 5u)                   \
  /* a new method: a line above this one */

#endif  // SST_CORE_MANYLIGHT_MANY_LIGHT_METHODS_H
