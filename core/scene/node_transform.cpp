#include "core/scene/node_transform.h"

#include <cmath>
#include <vector>

namespace sst {

glm::dmat4 trs_matrix(const glm::dvec3& translation, const glm::dvec4& rotation, const glm::dvec3& scale) {
  const glm::dvec4& q = rotation;
  double len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  double x = q.x / len, y = q.y / len, z = q.z / len, w = q.w / len;
  glm::dmat4 T(1.0), R(1.0);
  T[3] = glm::dvec4(translation, 1.0);
  R[0] = glm::dvec4(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0);
  R[1] = glm::dvec4(2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0);
  R[2] = glm::dvec4(2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0);
  glm::dmat4 S(glm::dvec4(scale.x, 0, 0, 0), glm::dvec4(0, scale.y, 0, 0), glm::dvec4(0, 0, scale.z, 0),
               glm::dvec4(0, 0, 0, 1));
  return T * R * S;
}

// The cofactor matrix (columns b x c, c x a, a x b) is the inverse transpose times det, so it
// transforms normals even when the matrix is singular.
WorldTransform world_transform(const glm::dmat4& m) {
  glm::dmat3 a(m);
  double det = glm::determinant(a);
  glm::dmat3 cof(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
  return {m, det < 0 ? -cof : cof, det < 0};
}

void set_geometric_normals(std::span<const vec3> positions, std::span<const uvec3> triangles, uint32_t first_vertex,
                           std::span<const char> needs, std::span<vec3> normals) {
  std::vector<char> seen(needs.size(), 0);
  for (uvec3 tri : triangles) {
    vec3 fn = face_normal(positions[tri.x], positions[tri.y], positions[tri.z]);
    if (!usable(fn)) continue;
    for (int k = 0; k < 3; ++k) {
      uint32_t i = tri[k] - first_vertex;
      if (i >= needs.size() || !needs[i]) continue;
      // The first face assigns rather than adds to zero, so that a flat-shaded vertex's normal
      // keeps the signs of zeros of its face's normal.
      normals[tri[k]] = seen[i] ? normals[tri[k]] + fn : fn;
      seen[i] = 1;
    }
  }
  for (size_t i = 0; i < needs.size(); ++i) {
    if (!needs[i]) continue;
    vec3& n = normals[first_vertex + i];
    n = seen[i] && usable(n) ? unit(n) : vec3(0.0f, 0.0f, 1.0f);
  }
}

bool place_camera(const glm::dmat4& world, Camera& camera) {
  glm::dvec3 f = glm::dmat3(world) * glm::dvec3(0, 0, -1), u = glm::dmat3(world) * glm::dvec3(0, 1, 0);
  double flen = glm::length(f);
  glm::dvec3 fn = f / flen;
  glm::dvec3 up = u - glm::dot(u, fn) * fn;  // Gram-Schmidt
  double ulen = glm::length(up);
  if (!(flen > 0.0) || !(ulen > 0.0) || !std::isfinite(flen + ulen)) return false;
  camera.eye = vec3(world[3]);
  camera.forward = vec3(fn);
  camera.up = vec3(up / ulen);
  return true;
}

bool place_light(const glm::dmat4& world, PunctualLight& light) {
  glm::dvec3 dir = glm::dmat3(world) * glm::dvec3(0, 0, -1);
  double len = glm::length(dir);
  if (light.type != LightType::Point && !(len > 0.0 && std::isfinite(len))) return false;
  light.position = vec3(world[3]);
  light.direction = len > 0.0 ? vec3(dir / len) : vec3(0.0f, 0.0f, -1.0f);
  return true;
}

}  // namespace sst
