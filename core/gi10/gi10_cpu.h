// gi10_stages.h bound to the CPU's memory: Gi10Buffers holds pointers to the stages' buffers, and
// the hooks read and write through them (atomics as GCC builtins, as the GPU's are GLSL's). The
// scene's, lights' and rays' hooks are those of Scene, PackedLights and EmbreeAccel. Included by
// the CPU executor (gi10_method.cpp) and the tests that drive single stages.
#pragma once
#include "core/accel/embree_accel.h"
#include "core/gi10/gi10_layout.h"
#include "core/lights/light_sampler.h"
#include "core/restir/restir_layout.h"
#include "core/shading/surface.h"

namespace sst {

// The CPU's buffers and the hooks of gi10_stages.h bound to them.
struct Gi10Buffers {
  const glsl::Gi10Frame* frame = nullptr;
  glsl::Gi10Pixel* pixels = nullptr;
  uint32_t* mask = nullptr;
  vec4* radiance = nullptr;
  vec4* sh = nullptr;
  uint32_t* spawn = nullptr;
  glsl::Gi10Ray* rays = nullptr;
  uint32_t* hash = nullptr;
  vec4* values = nullptr;
  uint32_t* accum = nullptr;
  vec4* emission = nullptr;
  vec4* denoise = nullptr;
  vec4* aux = nullptr;
  vec4* feedback = nullptr;
  uint32_t* counters = nullptr;
  vec4* output = nullptr;
  RestirReservoir* ray_reservoirs = nullptr;
  RestirReservoir* slot_reservoirs = nullptr;
  RestirSurface* slot_surfaces = nullptr;
};

inline uint32_t gi_atomic_cas(uint32_t& target, uint32_t compare, uint32_t value) {
  __atomic_compare_exchange_n(&target, &compare, value, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED);
  return compare;  // the value found, as GLSL's atomicCompSwap returns
}

inline uint32_t gi_atomic_min(uint32_t& target, uint32_t value) {
  uint32_t seen = __atomic_load_n(&target, __ATOMIC_RELAXED);
  while (value < seen && !__atomic_compare_exchange_n(&target, &seen, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
  return seen;  // the value found, as GLSL's atomicMin returns
}

}  // namespace sst

#define GI_CTX_PARAM const ::sst::Gi10Buffers &gi,
#define GI_CTX gi,
#define GF (*gi.frame)
#define GI_PIXELS(i) gi.pixels[i]
#define GI_MASK(i) gi.mask[i]
#define GI_RADIANCE(i) gi.radiance[i]
#define GI_SH(i) gi.sh[i]
#define GI_SPAWN(i) gi.spawn[i]
#define GI_RAYS(i) gi.rays[i]
#define GI_HASH(i) gi.hash[i]
#define GI_VALUES(i) gi.values[i]
#define GI_ACCUM(i) gi.accum[i]
#define GI_EMISSION(i) gi.emission[i]
#define GI_DENOISE(i) gi.denoise[i]
#define GI_AUX(i) gi.aux[i]
#define GI_FEEDBACK(i) gi.feedback[i]
#define GI_COUNTERS(i) gi.counters[i]
#define GI_OUTPUT(i) gi.output[i]
#define GI_RAY_RESERVOIRS(i) gi.ray_reservoirs[i]
#define GI_SLOT_RESERVOIRS(i) gi.slot_reservoirs[i]
#define GI_SLOT_SURFACES(i) gi.slot_surfaces[i]
#define GI_ATOMIC_ADD(ref, v) __atomic_fetch_add(&(ref), (v), __ATOMIC_RELAXED)
#define GI_ATOMIC_CAS(ref, compare, v) ::sst::gi_atomic_cas(ref, compare, v)
#define GI_ATOMIC_MIN(ref, v) ::sst::gi_atomic_min(ref, v)
#include "core/gi10/gi10_stages.h"
