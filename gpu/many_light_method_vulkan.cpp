#include "gpu/many_light_method_vulkan.h"

#include "core/manylight/sampler_inputs.h"
#include "core/vpl/vpl_ply.h"
#include "gpu/brsm_pass.h"
#include "gpu/gpu_render_context.h"
#include "gpu/light_tree_build_pass.h"
#include "gpu/many_light_pass.h"
#include "gpu/many_light_upload.h"
#include "gpu/vpl_generation_pass.h"

namespace sst::gpu {

FrameOutput VulkanManyLightMethod::render(const RenderContext& ctx, const GpuRenderContext& gpu, StageTimer& timer) {
  const VplParams& vpl_params = method_.vpl_params();
  const nlohmann::json params = method_.params();
  IndirectSampler& sampler = method_.sampler();
  FrameOutput frame;
  frame.allocate(ctx.width, ctx.height);

  VplStats vpl_stats;
  double vpl_gpu_ms = 0.0;
  const float view_distance = median_view_distance(ctx);
  VplSet vpls = timer.time("vpl_generation", [&] {
    const EmissionFocus focus = view_emission_focus(ctx, view_distance, vpl_params.directional_focus);
    if (vpl_params.vpl_source == "brsm") {
      VplSet set = generate_brsm_vpls_gpu(gpu.vulkan(), gpu.scene(), gpu.bvh(), gpu.lights(), ctx.lights.packed(),
                                          ctx.scene, vpl_params,
                                          view_params(ctx.camera, ctx.width, ctx.height, ctx.options.seed),
                                          ctx.options.seed, ctx.options.diffuse_only, &vpl_stats, focus, gpu.top_level());
      for (const auto& [stage, ms] : vpl_stats.stage_ms) vpl_gpu_ms += ms;
      return set;
    }
    return generate_vpls_gpu(gpu.vulkan(), gpu.scene(), gpu.bvh(), gpu.lights(), ctx.scene, vpl_params,
                             ctx.options.seed, ctx.options.diffuse_only, &vpl_stats, &vpl_gpu_ms, 0, focus,
                             gpu.top_level());
  });
  if (!vpl_params.export_vpls.empty()) write_vpls_ply(vpl_params.export_vpls, vpls);
  VplLighting lighting{ctx, vpls, vpl_stats.clamp_distance, vpl_stats.clamp_per_depth, view_distance};
  frame.method_counters["vpl"] = to_json(vpl_stats);
  frame.method_counters["view_distance"] = view_distance;
  // Radix and perfect trees are built on the GPU, agglomerative ones on the CPU. The builder's
  // shaders are compiled in stage shader_compile, like the sampling shader.
  auto on_gpu = [](const std::string& tree) { return tree == "radix" || tree == "perfect"; };
  std::unique_ptr<GpuLightTreeBuilder> tree_builder;
  double tree_gpu_ms = 0.0;
  if (on_gpu(params.value("tree", "")))
    tree_builder = timer.time("shader_compile", [&] { return std::make_unique<GpuLightTreeBuilder>(gpu.vulkan()); });
  sampler.set_tree_builder([&](const VplSet& v, const LightTreeParams& p, const TreeLengths* lengths,
                                 LightTreeBuildStats* stats, std::string* built_on) {
    if (!on_gpu(p.tree) || !tree_builder) return build_light_tree(v, p, lengths, stats);
    *built_on = "gpu";
    return tree_builder->build(v, p, lengths, stats, &tree_gpu_ms);
  });
  sampler.prepare(lighting, timer, frame.method_counters);
  sampler.set_tree_builder({});

  const SamplerInputs& in = sampler.inputs();
  auto inputs = timer.time("gpu_upload", [&] { return std::make_unique<GpuManyLightInputs>(gpu.vulkan(), in); });
  auto pipeline = timer.time("shader_compile", [&] { return make_many_light_pipeline(gpu, in.params); });
  ManyLightPassOutput out = timer.time("sampling", [&] {
    return render_many_light(gpu, *pipeline, *inputs, ctx.camera, ctx.options.seed, ctx.options.spp,
                             render_flags(ctx.options), vpl_params.clamp_compensation ? vpl_params.light_bounces() : 0,
                             vpl_params.vpl_min_bounces, frame);
  });

  frame.extra_layers = {{"indirect_variance", out.variance}, {"traversal_depth", out.traversal_depth}};
  frame.method_counters["indirect_samples"] = out.indirect_samples;
  frame.method_counters["nodes_visited_mean"] =
      out.indirect_samples ? double(out.nodes_visited) / double(out.indirect_samples) : 0.0;
  frame.method_counters["nodes_visited_histogram"] = out.depth_histogram;
  frame.method_counters["gpu_ms"] = {{"vpl_generation", vpl_gpu_ms}, {"sampling", out.gpu_ms}};
  if (tree_gpu_ms > 0.0) frame.method_counters["gpu_ms"]["tree_build"] = tree_gpu_ms;
  frame.method_counters["gpu"] = {{"sampling_dispatches", out.dispatches}};
  nlohmann::json built_on = {{"vpls", "gpu"}, {"sampling", "gpu"}};
  if (in.tree) built_on["tree"] = frame.method_counters["tree"].value("built_on", "cpu");
  if (!in.cut_nodes.empty()) built_on["cuts"] = "cpu";
  frame.method_counters["built_on"] = built_on;
  return frame;
}

}  // namespace sst::gpu
