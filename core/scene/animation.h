// Keyframe animation of a Scene's node hierarchy: rigid meshes, cameras and punctual lights that
// hang from animated nodes, posed at a time t. A neutral form (the glTF loader fills it; nothing
// here knows glTF): the nodes that move, their channels, and which parts of the Scene each one
// places. Only what moves is stored, so posing costs nothing for static parts.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/math/math.h"
#include "core/scene/scene.h"

namespace sst {

// A node of the hierarchy at rest. In a rig, a node that moves: the target of a channel or a
// descendant of one, whose rest values the channels that target it override.
struct RigNode {
  std::string name;
  int parent = -1;               // an earlier RigNode; -1: the parent does not move
  glm::dmat4 parent_world{1.0};  // the static parent's world matrix, when parent is -1
  std::optional<glm::dmat4> matrix;  // a fixed local matrix instead of T * R * S (never animated)
  glm::dvec3 translation{0.0};
  glm::dvec4 rotation{0.0, 0.0, 0.0, 1.0};  // quaternion [x, y, z, w], non-zero
  glm::dvec3 scale{1.0};

  glm::dmat4 local_matrix() const;
};

enum class AnimatedProperty { Translation, Rotation, Scale };
enum class Interpolation { Step, Linear, CubicSpline };
const char* interpolation_name(Interpolation i);  // glTF's spelling: STEP, LINEAR, CUBICSPLINE

struct AnimationChannel {
  std::string name;  // for messages and the summary, e.g. "animation 0 ('walk') channel 2"
  int node = 0;      // index into AnimationRig::nodes
  AnimatedProperty property = AnimatedProperty::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;   // seconds, finite and strictly increasing
  std::vector<double> values;  // 3 (rotation: 4) numbers a key; CubicSpline: in-tangent, value, out-tangent
};

// A mesh instance under an animated node: its vertices [first_vertex, + positions.size()) and
// triangles [first_triangle, + triangle_count) in the Scene, with the vertices in the node's
// object space. A normal that the node's transform makes unusable (zero: the file gave none, or
// a zero one) is the area-weighted normal of the vertex's triangles, as the loader makes it.
struct AnimatedMesh {
  int node = 0;
  uint32_t first_vertex = 0;
  uint32_t first_triangle = 0;
  uint32_t triangle_count = 0;
  std::vector<vec3> positions;
  std::vector<vec3> normals;
};

// A camera or light of the Scene (by index) that hangs from an animated node.
struct AnimatedAttachment {
  int node = 0;
  uint32_t index = 0;
};

struct AnimationRig {
  std::vector<RigNode> nodes;  // parents before children
  std::vector<AnimationChannel> channels;
  std::vector<AnimatedMesh> meshes;
  std::vector<AnimatedAttachment> cameras, lights;
  Bounds3 static_bounds;    // of every Scene vertex no animated mesh owns
  size_t vertex_count = 0;  // of the Scene posed, to refuse another
};

// What posing changed, so a renderer rebuilds only what it must.
struct PoseChange {
  bool geometry = false;
  bool cameras = false;
  bool lights = false;
};

class SceneAnimation {
 public:
  // Checks the rig's indices and key counts (a broken rig is a programming error: sst::Error).
  explicit SceneAnimation(AnimationRig rig);

  bool empty() const { return rig_.channels.empty(); }
  double start_time() const { return start_; }  // seconds: earliest key over all channels
  double end_time() const { return end_; }      // latest key

  // Poses `scene` (which the loader built, with the same vertex count and topology) at time t in
  // seconds: moves the vertices and normals of animated rigid meshes, animated cameras and
  // punctual lights; everything else is left as it is. t outside [start, end] clamps per channel
  // (glTF). A flag is set only when a value actually changed.
  PoseChange pose(Scene& scene, double t) const;

  // Channel count, animated nodes/cameras/lights/meshes, interpolations used, time range.
  nlohmann::json summary() const;

  const AnimationRig& rig() const { return rig_; }

 private:
  std::vector<glm::dmat4> node_worlds(double t) const;
  bool pose_mesh(const AnimatedMesh& mesh, const glm::dmat4& world, Scene& scene) const;

  AnimationRig rig_;
  double start_ = 0.0, end_ = 0.0;
};

// The value of one channel at time t (clamped to its keys): 3 or 4 numbers. Rotations come out
// by shortest-arc slerp (LINEAR) or normalised (CUBICSPLINE). Exposed for the tests.
glm::dvec4 sample_channel(const AnimationChannel& channel, double t);

}  // namespace sst
