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
  // Every node, leaves made as LightTree::node makes them where the tree stores none, written
  // straight into the mapped buffer (the shaders read a node as one buffer element: a GLSL function
  // returning a node made glslang's `precise` propagation exhaust memory).
  const size_t node_count = inputs.tree ? inputs.tree->node_count() : 0;
  nodes_ = make_buffer(context, node_count, sizeof(LightNode), "sampler tree nodes");
  if (node_count > 0) copy_nodes(*inputs.tree, {static_cast<LightNode*>(nodes_->data()), node_count});
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
