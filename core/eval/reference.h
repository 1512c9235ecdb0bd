// The reference a run is measured against, rendered once and cached by a hash of everything
// that determines its image, so it is reused across runs, sweeps and sessions.
//
// | reference key | default | meaning                                                               |
// |---------------|---------|-----------------------------------------------------------------------|
// | kind          | "path"  | "path": the path tracer (full ground truth); "vpl": exhaustive over    |
// |               |         | the run's own VPL set (same VPL parameters and seed): sampling error   |
// |               |         | only, without the VPL discretisation error                             |
// | spp           | 1024 / 64 | samples per pixel (path / vpl)                                       |
// | max_bounces   | 8       | path: indirect bounces                                                  |
// | seed          | 1000003 | path: its own seed, independent of every run's seed (vpl: the run's)   |
// | light_sampler | power   | path: the light sampler of its next-event estimation (RenderOptions)   |
// | mask          | false   | also measure each single-frame run on the pixels no directly seen      |
// |               |         | emitter touches ("masked" in its metrics): the mask is the scene's     |
// |               |         | emitters alone (emitters_only, core/scene/scene.h), 64 spp, cached     |
// | <parameter>   |         | any other pt (path) or exhaustive (vpl) parameter                     |
//
// Resolution, camera and diffuse_only are the run's. References always render on the CPU
// backend: they must not share a defect with the backend under test.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/eval/experiment_config.h"
#include "core/image/image.h"
#include "core/scene/scene.h"

namespace sst {

// Bumped when the renderers change what a reference image is; old cache entries then miss.
inline constexpr int kReferenceVersion = 1;

struct ReferenceSpec {
  std::string kind;     // "path" or "vpl"
  std::string scene;    // as the run names it
  nlohmann::json options;        // RenderOptions keys
  nlohmann::json method_params;  // pt or exhaustive parameters
  std::string id;       // 16 hex digits: hash of the above, the scene's content and kReferenceVersion
};

// The reference of `run` under the config's "reference" object. sst::Error for an unknown kind
// or key, or for a vpl reference of a run that has no VPLs (pt).
ReferenceSpec reference_for(const RunSpec& run, const nlohmann::json& reference_config,
                            const std::string& scene_content_hash);

// The emitter mask beside `reference` (its "mask" key): the same resolution and camera, pt with
// direct light only, diffuse-only, 64 spp; rendered on emitters_only(scene).
ReferenceSpec emitter_mask_for(const ReferenceSpec& reference);

// Hash of a scene's bytes: the .gltf/.glb and every external buffer and image it names
// ("" = the built-in scene).
std::string scene_content_hash(const std::string& scene_path);

// Where references are kept: SST_CACHE_DIR, else $XDG_CACHE_HOME/sst/references, else
// ~/.cache/sst/references.
std::string default_reference_cache_dir();

class ReferenceCache {
 public:
  explicit ReferenceCache(std::string dir);
  // The reference image (linear RGB): read from the cache, or rendered, written atomically
  // (<id>.exr and <id>.json, the render's record) and returned. `record` receives the JSON record.
  Image get(const ReferenceSpec& spec, const Scene& scene, bool quiet, nlohmann::json* record = nullptr);
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
};

}  // namespace sst
