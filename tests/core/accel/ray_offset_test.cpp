// The error-bounded ray offsets (core/accel/ray_offset.h): a ray leaving a surface point lifted by
// its Surface::offset never meets its own triangle again, on Embree and on the flat BVH, also on
// scenes moved far from the origin and at grazing angles; with no lift it does (so the test can
// fail).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "core/accel/embree_accel.h"
#include "core/accel/ray_offset.h"
#include "core/render/camera.h"
#include "core/sampling/sampling.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/shading/surface.h"
#include "tests/test_util.h"

namespace sst {
namespace {

struct SelfHits {
  size_t rays = 0, lifted = 0, unlifted = 0;
};

// Camera rays to random pixels; from each hit, one ray into the hemisphere (every fourth one
// within 0.6 degrees of grazing), once lifted by the surface's offset and once from the point itself.
SelfHits count_self_hits(const Scene& scene, const EmbreeAccel& accel, int rays) {
  PinholeCamera camera(scene.cameras.at(0), 256, 256);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SelfHits out;
  for (int i = 0; i < rays; ++i) {
    Ray primary = camera.generate(256.0f * u(rng), 256.0f * u(rng));
    Hit hit = accel.intersect(primary);
    if (!hit.valid()) continue;
    Surface s = make_surface(scene, hit, primary.direction);
    vec3 local = sample_cosine_hemisphere(u(rng), u(rng));
    if (i % 4 == 0) {  // grazing: cos theta in (0, 0.01)
      const float c = 0.01f * u(rng) + 1e-6f, phi = 6.2831853f * u(rng);
      const float r = std::sqrt(1.0f - c * c);
      local = vec3(r * std::cos(phi), r * std::sin(phi), c);
    }
    const vec3 dir = to_world(basis_from_normal(s.ng), local);
    ++out.rays;
    Ray ray;
    ray.direction = dir;
    ray.origin = offset_ray_origin(s.offset, s.p, s.ng);
    out.lifted += accel.intersect(ray).triangle == s.triangle;
    ray.origin = s.p;
    out.unlifted += accel.intersect(ray).triangle == s.triangle;
  }
  return out;
}

void translate(Scene& scene, vec3 t) {
  for (vec3& p : scene.positions) p += t;
  for (Camera& c : scene.cameras) c.eye += t;
  for (PunctualLight& l : scene.lights) l.position += t;
  scene.finalize_bounds();
}

TEST(RayOffset, RaysLeavingASurfaceNeverMeetItAgain) {
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("cornell-box", load_default_scene());
  for (float far : {1e4f, 1e5f}) {
    Scene moved = load_default_scene();
    translate(moved, vec3(far, -0.5f * far, 0.25f * far));
    scenes.emplace_back("cornell-box at " + std::to_string(int(far)) + " m", std::move(moved));
  }
  for (const char* shared : {"breakfast-room/breakfast-room.gltf", "staircase/staircase.gltf"})
    if (auto path = test::shared_scene(shared); !path.empty()) scenes.emplace_back(shared, load_gltf(path.string()));
  for (const auto& [name, scene] : scenes) {
    for (bool flat : {false, true}) {
      SCOPED_TRACE(name + (flat ? " (flat BVH)" : " (Embree)"));
      EmbreeAccel accel(scene, flat);
      const SelfHits h = count_self_hits(scene, accel, 50000);
      std::printf("[ray offset] %-40s %-8s %zu rays: %zu meet their own triangle lifted, %zu unlifted\n",
                  name.c_str(), flat ? "flat" : "embree", h.rays, h.lifted, h.unlifted);
      EXPECT_GT(h.rays, 25000u);
      EXPECT_EQ(h.lifted, 0u);
      EXPECT_GT(h.unlifted, 0u) << "without the lift rays meet their surface: the test can fail";
    }
  }
}

}  // namespace
}  // namespace sst
