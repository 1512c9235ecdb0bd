#include "gpu/vulkan_method.h"

#include "core/gi10/gi10_method.h"
#include "core/manylight/many_light_method.h"
#include "core/pt/path_tracer.h"
#include "core/util/error.h"
#include "gpu/gi10_vulkan.h"
#include "gpu/restir_gi_vulkan.h"
#include "gpu/many_light_method_vulkan.h"
#include "gpu/path_tracer_vulkan.h"

namespace sst::gpu {

std::unique_ptr<VulkanMethod> make_vulkan_method(Method& method, const std::string& name) {
  if (auto* pt = dynamic_cast<PathTracer*>(&method)) return std::make_unique<VulkanPathTracer>(*pt);
  if (auto* many_light = dynamic_cast<ManyLightMethod*>(&method))
    return std::make_unique<VulkanManyLightMethod>(*many_light);
  if (auto* gi10 = dynamic_cast<Gi10Method*>(&method)) return std::make_unique<VulkanGi10>(*gi10);
  if (auto* gi = dynamic_cast<RestirGi*>(&method)) return std::make_unique<VulkanRestirGi>(*gi);
  throw Error("method '" + name + "' has no Vulkan port yet; use --backend cpu");
}

}  // namespace sst::gpu
