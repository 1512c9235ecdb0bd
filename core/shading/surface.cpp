#include "core/shading/surface.h"

namespace sst {
namespace {
vec2 interpolate_uv(const Scene& scene, const uvec3& t, vec2 b) {
  if (scene.uvs.empty()) return vec2(0.0f);
  return (1.0f - b.x - b.y) * scene.uvs[t.x] + b.x * scene.uvs[t.y] + b.y * scene.uvs[t.z];
}

vec4 texture_or_one(const Scene& scene, int texture, vec2 uv) {
  return texture >= 0 && size_t(texture) < scene.textures.size() ? scene.textures[texture].sample(uv) : vec4(1.0f);
}
}  // namespace

vec3 triangle_geometric_normal(const Scene& scene, uint32_t tri) {
  const uvec3& t = scene.triangles[tri];
  vec3 n = glm::cross(scene.positions[t.y] - scene.positions[t.x], scene.positions[t.z] - scene.positions[t.x]);
  float len = glm::length(n);
  return len > 0.0f ? n / len : vec3(0.0f, 0.0f, 1.0f);
}

float triangle_area(const Scene& scene, uint32_t tri) {
  const uvec3& t = scene.triangles[tri];
  return 0.5f * glm::length(glm::cross(scene.positions[t.y] - scene.positions[t.x],
                                       scene.positions[t.z] - scene.positions[t.x]));
}

vec3 triangle_emission(const Scene& scene, uint32_t tri, vec2 barycentric, bool front_face) {
  const Material& m = scene.materials[scene.triangle_material[tri]];
  if (!front_face && !m.double_sided) return vec3(0.0f);
  if (m.emissive_texture < 0) return m.emission;
  vec2 uv = interpolate_uv(scene, scene.triangles[tri], barycentric);
  return m.emission * vec3(texture_or_one(scene, m.emissive_texture, uv));
}

Surface make_surface(const Scene& scene, const Hit& hit, vec3 incoming) {
  Surface s;
  const uvec3& t = scene.triangles[hit.triangle];
  vec2 b = hit.barycentric;
  float b0 = 1.0f - b.x - b.y;
  // Recompute the point from the triangle rather than origin + t*dir: it is exact on the surface.
  s.p = b0 * scene.positions[t.x] + b.x * scene.positions[t.y] + b.y * scene.positions[t.z];
  s.triangle = hit.triangle;
  s.material = scene.triangle_material[hit.triangle];
  s.ng = triangle_geometric_normal(scene, hit.triangle);
  s.front_face = glm::dot(s.ng, incoming) < 0.0f;
  if (!s.front_face) s.ng = -s.ng;
  vec3 ns = b0 * scene.normals[t.x] + b.x * scene.normals[t.y] + b.y * scene.normals[t.z];
  float len = glm::length(ns);
  ns = len > 0.0f && std::isfinite(len) ? ns / len : s.ng;
  // Shading normals are interpolated per vertex and may point away from the viewer's side;
  // keep them in the hemisphere of the geometric normal so shading never sees a back face.
  if (glm::dot(ns, s.ng) < 0.0f) ns = -ns;
  s.ns = ns;
  s.uv = interpolate_uv(scene, t, b);

  const Material& m = scene.materials[s.material];
  s.base_color = m.base_color * vec3(texture_or_one(scene, m.base_color_texture, s.uv));
  vec4 mr = texture_or_one(scene, m.metallic_roughness_texture, s.uv);
  s.metallic = m.metallic * mr.z;
  s.roughness = m.roughness * mr.y;
  s.emission = triangle_emission(scene, hit.triangle, b, s.front_face);
  return s;
}

}  // namespace sst
