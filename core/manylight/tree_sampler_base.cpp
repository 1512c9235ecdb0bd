#include "core/manylight/tree_sampler_base.h"

namespace sst {

TreeSamplerBase::TreeSamplerBase(LightTreeParams params) : tree_params_(std::move(params)) { validate(tree_params_); }

void TreeSamplerBase::build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters,
                            SamplerInputs& inputs) {
  LightTreeBuildStats stats;
  // D = view: the diameter of the sphere around the camera through the median of what it sees,
  // close to the VPLs' bounding-box diagonal in the shared interiors (0.9-3x the median distance).
  const TreeLengths lengths{lighting.context.scene.bounds, 2.0f * lighting.view_distance};
  std::string built_on = "cpu";
  timer.time("tree_build", [&] {
    if (builder_)
      tree_ = builder_(lighting.vpls, tree_params_, &lengths, &stats, &built_on);
    else
      cpu_builder_.build(lighting.vpls, tree_params_, &lengths, tree_, &stats);
  });
  const float node_floor = node_distance_floor_for(tree_params_, tree_.vpl_bounds, lengths.view);
  // What node_distance_floor_above is compared with, so that a record shows how near the threshold a scene is.
  const float vpl_view_lengths =
      tree_.vpl_bounds.empty() || !(lengths.view > 0.0f) ? 0.0f : tree_.vpl_bounds.diagonal() / lengths.view;
  counters["tree"] = {{"kind", tree_.kind},
                      {"built_on", built_on},
                      {"nodes", tree_.node_count()},
                      {"height", tree_height(tree_)},
                      {"suitable_internal", count_suitable_internal(tree_)},
                      {"length_scale", tree_.length_scale},
                      {"node_distance_floor", node_floor},
                      {"vpl_view_lengths", vpl_view_lengths},
                      {"bounds_ms", stats.bounds_ms},
                      {"keys_ms", stats.keys_ms},
                      {"sort_ms", stats.sort_ms},
                      {"hierarchy_ms", stats.hierarchy_ms},
                      {"merge_ms", stats.merge_ms},
                      {"total_ms", stats.total_ms}};
  set_tree_inputs(tree_, inputs);
  inputs.params.substitute_max_extent = tree_params_.substitute_max_extent;
  inputs.params.node_distance_floor = node_floor;
}

}  // namespace sst
