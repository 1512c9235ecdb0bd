// GI-1.0's stages, all of them (gi10_buffers.h says how they are written for both backends), and
// the one entry both backends call for an element of a stage.
#ifndef SST_CORE_GI10_GI10_STAGES_H
#define SST_CORE_GI10_GI10_STAGES_H
#include "core/gi10/gi10_cache.h"
#include "core/gi10/gi10_probes.h"
#include "core/gi10/gi10_resolve.h"

SST_BEGIN

// Element `index` of stage `requested_stage` (GI10_STAGE_*): the one entry both backends call.
// `pass`: the mask level of MASK_MIP, the direction of FILTER and FILTER_GI, the step of
// SIDE_LOOKUP and SIDE_REORDER.
SST_FUNC void gi10_stage(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint requested_stage, uint pass,
                         uint index) {
#ifdef GI10_SHADER_STAGE
  // A shader built for one stage (gpu/shaders/gi10.comp) compares a constant, so that its front end
  // drops the other stages before glslc's optimiser inlines them: with all 27 inlined and then
  // removed, a stage took 6-10 s to compile instead of under 1 s, for SPIR-V of the same size.
  const uint stage = GI10_SHADER_STAGE < GI10_STAGES ? GI10_SHADER_STAGE : GI10_STAGE_SHADE;
#else
  const uint stage = requested_stage;
#endif
  uint cur = gi_parity(GF);
  if (stage == GI10_STAGE_GBUFFER) gi_stage_gbuffer(SCENE_CTX RAY_CTX GI_CTX index);
  else if (stage == GI10_STAGE_PURGE) gi_stage_purge(GI_CTX index);
  else if (stage == GI10_STAGE_REPROJECT) gi_stage_reproject(GI_CTX index);
  else if (stage == GI10_STAGE_SPAWN) gi_stage_spawn(GI_CTX index);
  else if (stage == GI10_STAGE_EMPTY_TILES) gi_stage_empty_tiles(GI_CTX index);
  else if (stage == GI10_STAGE_LIST_COUNT) gi_stage_list_count(GI_CTX index);
  else if (stage == GI10_STAGE_LIST_SCAN) gi_stage_list_scan(GI_CTX index);
  else if (stage == GI10_STAGE_LIST_COMPACT) gi_stage_list_compact(GI_CTX index);
  else if (stage == GI10_STAGE_PATCH) gi_stage_patch(GI_CTX index);
  else if (stage == GI10_STAGE_SAMPLE) gi_stage_sample(GI_CTX index);
  else if (stage == GI10_STAGE_TRACE) gi_stage_trace(SCENE_CTX RAY_CTX GI_CTX index);
  else if (stage == GI10_STAGE_SHADE) gi_stage_shade(SCENE_CTX LIGHT_CTX RAY_CTX GI_CTX index);
  else if (stage == GI10_STAGE_STORE_RESERVOIR) gi_stage_store_reservoir(GI_CTX index);
  else if (stage == GI10_STAGE_UPDATE) gi_stage_update(GI_CTX index);
  else if (stage == GI10_STAGE_RESOLVE) gi_stage_resolve(GI_CTX index);
  else if (stage == GI10_STAGE_BLEND) gi_stage_blend(GI_CTX index);
  else if (stage == GI10_STAGE_MASK_MIP) gi_stage_mask_mip(GI_CTX pass, index);
  else if (stage == GI10_STAGE_COPY_PROBES) gi_stage_copy_probes(GI_CTX cur, cur ^ 1u, index);
  else if (stage == GI10_STAGE_FILTER) gi_stage_filter(GI_CTX pass, pass == 0u ? cur : cur ^ 1u, pass == 0u ? cur ^ 1u : cur, index);
  else if (stage == GI10_STAGE_PROJECT) gi_stage_project(GI_CTX index);
  else if (stage == GI10_STAGE_INTERPOLATE) gi_stage_interpolate(GI_CTX index);
  else if (stage == GI10_STAGE_DENOISE_REPROJECT) gi_stage_denoise_reproject(GI_CTX index);
  else if (stage == GI10_STAGE_BLUR_MASK) gi_stage_blur_mask(GI_CTX index);
  else if (stage == GI10_STAGE_FILTER_GI) gi_stage_filter_gi(GI_CTX pass, index);
  else if (stage == GI10_STAGE_FEEDBACK) gi_stage_feedback_image(GI_CTX index);
  else if (stage == GI10_STAGE_SIDE_LOOKUP) gi_stage_side_lookup(GI_CTX pass, index);
  else if (stage == GI10_STAGE_SIDE_ALLOCATE) gi_stage_side_allocate(GI_CTX index);
  else if (stage == GI10_STAGE_SIDE_REORDER) gi_stage_side_reorder(GI_CTX pass, index);
}

SST_END

#endif  // SST_CORE_GI10_GI10_STAGES_H
