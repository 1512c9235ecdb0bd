#include "gpu/many_light_upload.h"

namespace sst::gpu {

std::vector<GpuVpl> pack_vpls(std::span<const Vpl> vpls) {
  std::vector<GpuVpl> out(vpls.size());
  for (size_t i = 0; i < vpls.size(); ++i) {
    out[i] = {};
    out[i].position = vpls[i].position;
    out[i].normal = vpls[i].normal;
    out[i].intensity = vpls[i].intensity;
  }
  return out;
}


GpuManyLightInputs::GpuManyLightInputs(const VulkanContext& context, const SamplerInputs& inputs)
    : params_(inputs.params) {
  std::vector<GpuVpl> packed = pack_vpls(inputs.vpls);
  params_buffer_ = upload_buffer(context, std::span<const SamplerParams>(&params_, 1), "sampler parameters");
  vpls_ = upload_buffer(context, std::span<const GpuVpl>(packed), "sampler VPLs");
  // Every node, leaves made as LightTree::node makes them where the tree stores none (the shaders
  // read a node as one buffer element: a GLSL function returning a node made glslang's `precise`
  // propagation exhaust memory).
  std::vector<LightNode> made;
  std::span<const LightNode> nodes;
  if (inputs.tree && inputs.tree->stored_nodes == inputs.tree->node_count()) {
    nodes = inputs.tree->nodes;
  } else if (inputs.tree) {
    made.resize(inputs.tree->node_count());
    for (uint32_t i = 0; i < made.size(); ++i) made[i] = inputs.tree->node(i);
    nodes = made;
  }
  nodes_ = upload_buffer(context, nodes, "sampler tree nodes");
  cut_nodes_ = upload_buffer(context, inputs.cut_nodes, "sampler cut nodes");
  cut_sizes_ = upload_buffer(context, inputs.cut_sizes, "sampler cut sizes");
  guides_ = upload_buffer(context, std::span<const CutGuide>(inputs.guides), "sampler cut guides");
  mock_cut_ = upload_buffer(context, inputs.mock_cut, "sampler mock cut");
}

std::vector<const GpuBuffer*> GpuManyLightInputs::buffers() const {
  return {params_buffer_.get(), vpls_.get(), nodes_.get(), cut_nodes_.get(), cut_sizes_.get(), guides_.get(),
          mock_cut_.get()};
}

size_t GpuManyLightInputs::bytes() const {
  size_t total = 0;
  for (const GpuBuffer* b : buffers()) total += b->size();
  return total;
}

}  // namespace sst::gpu
