// Sampling a triangle uniformly by the solid angle it subtends from a point (Arvo, "Stratified
// Sampling of Spherical Triangles", SIGGRAPH 1995; the formulation of pbrt-v4). For an emitter
// close to the shading point this removes the 1/d^2 spike of area sampling, which otherwise
// makes fireflies where a light nearly touches a surface (the Cornell box's lamp, 1 cm below
// its ceiling). Cycles samples mesh lights the same way, so noise levels compare fairly.
#pragma once
#include "core/math/math.h"

namespace sst {

// Solid angle of triangle (v0, v1, v2) seen from p (Van Oosterom & Strackee 1983).
float triangle_solid_angle(vec3 p, vec3 v0, vec3 v1, vec3 v2);

// Barycentrics (b1, b2) of the point hit by a direction drawn uniformly over the spherical
// triangle; *pdf receives 1 / solid angle. Returns false for a degenerate spherical triangle.
bool sample_spherical_triangle(vec3 p, vec3 v0, vec3 v1, vec3 v2, vec2 u, vec2* barycentric, float* pdf);

// Solid angles in which spherical sampling is numerically safe and worth it (pbrt-v4's bounds):
// below, the triangle is small enough that area sampling is as good; above, it nearly fills the
// hemisphere and the spherical formulas lose precision.
inline constexpr float kMinSphericalSolidAngle = 3e-4f;
inline constexpr float kMaxSphericalSolidAngle = 6.22f;

}  // namespace sst
