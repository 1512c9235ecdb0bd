#include "gpu/many_light_upload.h"

namespace sst::gpu {

std::vector<glsl::GpuVpl> pack_vpls(const VplSet& vpls) {
  std::vector<glsl::GpuVpl> out(vpls.size());
  for (size_t i = 0; i < vpls.size(); ++i) {
    out[i] = {};
    out[i].position = vpls[i].position;
    out[i].normal = vpls[i].normal;
    out[i].intensity = vpls[i].intensity;
  }
  return out;
}

namespace {

// A buffer holding `values`, or a 16-byte dummy for an empty array.
template <class T>
std::unique_ptr<GpuBuffer> upload_array(const VulkanContext& context, std::span<const T> values) {
  auto buffer = std::make_unique<GpuBuffer>(context, values.empty() ? 16 : values.size_bytes());
  if (!values.empty()) buffer->upload(values);
  return buffer;
}

}  // namespace

GpuManyLightInputs::GpuManyLightInputs(const VulkanContext& context, const VplSet& vpls,
                                       const GpuSamplerInputs& inputs)
    : params_(inputs.params) {
  std::vector<glsl::GpuVpl> packed = pack_vpls(vpls);
  params_.vpl_count = uint32_t(packed.size());
  params_buffer_ = upload_array(context, std::span<const glsl::SamplerParams>(&params_, 1));
  vpls_ = upload_array(context, std::span<const glsl::GpuVpl>(packed));
  nodes_ = upload_array(context, inputs.nodes);
  cut_nodes_ = upload_array(context, inputs.cut_nodes);
  cut_sizes_ = upload_array(context, inputs.cut_sizes);
  guides_ = upload_array(context, std::span<const glsl::CutGuide>(inputs.guides));
  mock_cut_ = upload_array(context, inputs.mock_cut);
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
