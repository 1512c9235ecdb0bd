#include "core/scene/animation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <set>

#include "core/scene/node_transform.h"
#include "core/util/error.h"

namespace sst {
namespace {

int components(AnimatedProperty p) { return p == AnimatedProperty::Rotation ? 4 : 3; }

// Keys nearly parallel make sin(theta) vanish; there the chord and the arc agree.
glm::dvec4 slerp(glm::dvec4 a, glm::dvec4 b, double s) {
  double d = glm::dot(a, b) / std::sqrt(glm::dot(a, a) * glm::dot(b, b));
  if (d < 0.0) {  // q and -q are the same rotation: take the shorter arc
    b = -b;
    d = -d;
  }
  if (d > 1.0 - 1e-12) return a + (b - a) * s;  // exact at equal keys; trs_matrix normalises
  double theta = std::acos(d);
  double sin_theta = std::sin(theta);
  return (std::sin((1.0 - s) * theta) / sin_theta) * glm::normalize(a) + (std::sin(s * theta) / sin_theta) * glm::normalize(b);
}

// Only the finite, non-zero quaternions a cubic spline can also produce make a rotation.
bool usable_rotation(const glm::dvec4& q) {
  double len2 = glm::dot(q, q);
  return len2 > 0.0 && std::isfinite(len2);
}

bool same_bits(vec3 a, vec3 b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

glm::dmat4 RigNode::local_matrix() const { return matrix ? *matrix : trs_matrix(translation, rotation, scale); }

const char* interpolation_name(Interpolation i) {
  switch (i) {
    case Interpolation::Step: return "STEP";
    case Interpolation::Linear: return "LINEAR";
    case Interpolation::CubicSpline: return "CUBICSPLINE";
  }
  return "?";
}

glm::dvec4 sample_channel(const AnimationChannel& c, double t) {
  size_t comps = size_t(components(c.property));
  bool cubic = c.interpolation == Interpolation::CubicSpline;
  size_t stride = cubic ? 3 * comps : comps;
  // part: 0 = in-tangent, 1 = value, 2 = out-tangent (CubicSpline); the value otherwise.
  auto key = [&](size_t k, size_t part) {
    const double* p = c.values.data() + k * stride + (cubic ? part : 0) * comps;
    return glm::dvec4(p[0], p[1], p[2], comps == 4 ? p[3] : 0.0);
  };
  const std::vector<double>& times = c.times;
  if (!(t > times.front())) return key(0, 1);  // also NaN: the first key
  if (t >= times.back()) return key(times.size() - 1, 1);
  size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  double dt = times[k + 1] - times[k];
  double s = (t - times[k]) / dt;
  bool rotation = c.property == AnimatedProperty::Rotation;
  switch (c.interpolation) {
    case Interpolation::Step: return key(k, 1);
    case Interpolation::Linear: {
      glm::dvec4 a = key(k, 1), b = key(k + 1, 1);
      return rotation ? slerp(a, b, s) : a + (b - a) * s;
    }
    case Interpolation::CubicSpline: {
      double s2 = s * s, s3 = s2 * s;
      glm::dvec4 v = (2 * s3 - 3 * s2 + 1) * key(k, 1) + (s3 - 2 * s2 + s) * dt * key(k, 2) +
                     (-2 * s3 + 3 * s2) * key(k + 1, 1) + (s3 - s2) * dt * key(k + 1, 0);
      return rotation && usable_rotation(v) ? glm::normalize(v) : v;
    }
  }
  return key(k, 1);
}

SceneAnimation::SceneAnimation(AnimationRig rig) : rig_(std::move(rig)) {
  auto broken = [](const std::string& what) { throw Error("animation rig: " + what); };
  int node_count = int(rig_.nodes.size());
  for (int i = 0; i < node_count; ++i)
    if (rig_.nodes[i].parent >= i) broken("node " + std::to_string(i) + " comes before its parent");
  auto check_node = [&](int node, const std::string& what) {
    if (node < 0 || node >= node_count) broken(what + " refers to missing node " + std::to_string(node));
  };
  start_ = kInf;
  end_ = -kInf;
  for (const AnimationChannel& c : rig_.channels) {
    check_node(c.node, c.name);
    size_t per_key = size_t(components(c.property)) * (c.interpolation == Interpolation::CubicSpline ? 3 : 1);
    if (c.times.empty() || c.values.size() != c.times.size() * per_key) broken(c.name + " has mismatched keys and values");
    if (rig_.nodes[c.node].matrix) broken(c.name + " targets a node with a fixed matrix");
    start_ = std::min(start_, c.times.front());
    end_ = std::max(end_, c.times.back());
  }
  if (rig_.channels.empty()) start_ = end_ = 0.0;
  for (const AnimatedMesh& m : rig_.meshes) {
    check_node(m.node, "a mesh");
    if (m.normals.size() != m.positions.size() || m.first_vertex + m.positions.size() > rig_.vertex_count)
      broken("a mesh's vertices lie outside the scene");
  }
  for (const auto* list : {&rig_.cameras, &rig_.lights})
    for (const AnimatedAttachment& a : *list) check_node(a.node, "a camera or light");
}

std::vector<glm::dmat4> SceneAnimation::node_worlds(double t) const {
  std::vector<RigNode> posed = rig_.nodes;
  for (const AnimationChannel& c : rig_.channels) {
    glm::dvec4 v = sample_channel(c, t);
    RigNode& n = posed[c.node];
    switch (c.property) {
      case AnimatedProperty::Translation: n.translation = glm::dvec3(v); break;
      case AnimatedProperty::Rotation:
        if (usable_rotation(v)) n.rotation = v;  // else the rest rotation: a spline through zero
        break;
      case AnimatedProperty::Scale: n.scale = glm::dvec3(v); break;
    }
  }
  std::vector<glm::dmat4> worlds(posed.size());
  for (size_t i = 0; i < posed.size(); ++i) {
    const RigNode& n = posed[i];
    worlds[i] = (n.parent >= 0 ? worlds[n.parent] : n.parent_world) * n.local_matrix();
  }
  return worlds;
}

// Vertices transform in parallel; normals the transform makes unusable are then rebuilt from
// the faces in triangle order, as the loader builds them, so the rest pose gives its bits.
bool SceneAnimation::pose_mesh(const AnimatedMesh& mesh, const glm::dmat4& world, Scene& scene) const {
  WorldTransform tf = world_transform(world);
  size_t n = mesh.positions.size();
  std::vector<char> needs(n, 0);
  std::atomic<bool> any_needs{false}, changed{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
    bool local_changed = false, local_needs = false;
    for (size_t i = r.begin(); i < r.end(); ++i) {
      size_t v = mesh.first_vertex + i;
      vec3 p = transform_point(tf, mesh.positions[i]);
      vec3 wn = transform_normal(tf, mesh.normals[i]);
      needs[i] = !usable(wn);
      local_needs |= bool(needs[i]);
      vec3 normal = needs[i] ? scene.normals[v] : unit(wn);
      local_changed |= !same_bits(p, scene.positions[v]) || !same_bits(normal, scene.normals[v]);
      scene.positions[v] = p;
      scene.normals[v] = normal;
    }
    if (local_changed) changed = true;
    if (local_needs) any_needs = true;
  });
  if (any_needs) {
    std::vector<vec3> before(scene.normals.begin() + mesh.first_vertex, scene.normals.begin() + mesh.first_vertex + n);
    set_geometric_normals(scene.positions,
                          std::span<const uvec3>(scene.triangles).subspan(mesh.first_triangle, mesh.triangle_count),
                          mesh.first_vertex, needs, scene.normals);
    for (size_t i = 0; i < n && !changed; ++i)
      if (needs[i] && !same_bits(before[i], scene.normals[mesh.first_vertex + i])) changed = true;
  }
  return changed;
}

PoseChange SceneAnimation::pose(Scene& scene, double t) const {
  if (scene.positions.size() != rig_.vertex_count || scene.normals.size() != rig_.vertex_count)
    throw Error(scene.source + ": cannot pose a scene of " + std::to_string(scene.positions.size()) +
                " vertices with an animation made for " + std::to_string(rig_.vertex_count));
  PoseChange change;
  if (empty()) return change;
  std::vector<glm::dmat4> worlds = node_worlds(t);
  for (const AnimatedMesh& m : rig_.meshes) change.geometry |= pose_mesh(m, worlds[m.node], scene);
  if (change.geometry) {
    // Static vertices keep their part of the box; min/max do not depend on order, so this is
    // the box finalize_bounds() would compute.
    scene.bounds = rig_.static_bounds;
    for (const AnimatedMesh& m : rig_.meshes)
      for (size_t i = 0; i < m.positions.size(); ++i) scene.bounds.extend(scene.positions[m.first_vertex + i]);
  }
  // A node matrix that collapses a camera's or a light's axes leaves it where it was.
  for (const AnimatedAttachment& a : rig_.cameras) {
    Camera& c = scene.cameras.at(a.index);
    Camera before = c;
    if (place_camera(worlds[a.node], c))
      change.cameras |= !same_bits(c.eye, before.eye) || !same_bits(c.forward, before.forward) || !same_bits(c.up, before.up);
  }
  for (const AnimatedAttachment& a : rig_.lights) {
    PunctualLight& l = scene.lights.at(a.index);
    PunctualLight before = l;
    if (place_light(worlds[a.node], l))
      change.lights |= !same_bits(l.position, before.position) || !same_bits(l.direction, before.direction);
  }
  return change;
}

nlohmann::json SceneAnimation::summary() const {
  std::set<std::string> interpolations;
  size_t vertices = 0;
  for (const AnimationChannel& c : rig_.channels) interpolations.insert(interpolation_name(c.interpolation));
  for (const AnimatedMesh& m : rig_.meshes) vertices += m.positions.size();
  return {{"channels", rig_.channels.size()},
          {"animated_nodes", rig_.nodes.size()},
          {"animated_meshes", rig_.meshes.size()},
          {"animated_vertices", vertices},
          {"animated_cameras", rig_.cameras.size()},
          {"animated_lights", rig_.lights.size()},
          {"interpolations", interpolations},
          {"start_time", start_},
          {"end_time", end_}};
}

}  // namespace sst
