// How a node's matrix places what hangs from it in the world: vertices, normals, cameras and
// punctual lights. The glTF loader and the animation's posing share these, so that posing at the
// rest pose gives the loader's bits.
#pragma once
#include <glm/glm.hpp>
#include <span>

#include "core/math/math.h"
#include "core/scene/scene.h"

namespace sst {

// T * R * S in double; `rotation` is a quaternion [x, y, z, w] (glTF's order) of non-zero length,
// renormalised here because files store it with float precision.
glm::dmat4 trs_matrix(const glm::dvec3& translation, const glm::dvec4& rotation, const glm::dvec3& scale);

struct WorldTransform {
  glm::dmat4 m;
  glm::dmat3 normal;  // the cofactor matrix, sign-corrected: the inverse transpose up to scale
  bool mirrored;      // negative determinant: triangles' winding is flipped to keep their facing
};
WorldTransform world_transform(const glm::dmat4& m);

inline vec3 transform_point(const WorldTransform& t, vec3 p) { return vec3(t.m * glm::dvec4(glm::dvec3(p), 1.0)); }
// Unnormalised; judge it with usable() before unit().
inline vec3 transform_normal(const WorldTransform& t, vec3 n) { return vec3(t.normal * glm::dvec3(n)); }

// Unnormalised geometric normal of a triangle, oriented by its winding.
inline vec3 face_normal(vec3 a, vec3 b, vec3 c) { return glm::cross(b - a, c - a); }
// Judged and normalised by the largest component, because the squared length of a tiny
// triangle's cross product (edges ~1e-12) underflows in float although the direction is fine.
inline bool usable(vec3 n) { return is_finite(n) && max_component(glm::abs(n)) > 0.0f; }
inline vec3 unit(vec3 n) { return glm::normalize(n / max_component(glm::abs(n))); }

// Area-weighted geometric normals (what a vertex without a usable normal gets): each vertex
// first_vertex + i with needs[i] set gets the unit sum of face_normal() over the `triangles`
// that use it and have a usable one, or +Z when none has. Positions and normals are the whole
// Scene arrays, indexed as the triangles index them.
void set_geometric_normals(std::span<const vec3> positions, std::span<const uvec3> triangles, uint32_t first_vertex,
                           std::span<const char> needs, std::span<vec3> normals);

// A camera node looks down its -Z with +Y up: sets eye, forward and up (orthogonalised, so shear
// in the matrix is dropped). False, leaving the camera as it was, when the matrix collapses
// either axis.
bool place_camera(const glm::dmat4& world, Camera& camera);

// A light node shines down its -Z: sets position and direction. False, leaving the light as it
// was, when a spot or directional light's direction collapses; a point light needs none.
bool place_light(const glm::dmat4& world, PunctualLight& light);

}  // namespace sst
