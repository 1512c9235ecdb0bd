// The node hierarchy of a glTF scene: each node's rest transform, checked, and the hierarchy
// flattened into instances with world matrices. The loader places meshes, cameras and lights by
// the instances, and the animation rig (gltf_animation.h) starts from the same rest transforms
// and instances, so both read them here.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "core/scene/animation.h"
#include "core/scene/gltf_context.h"

namespace sst::gltf {

// A node as the traversal meets it: a node with one parent (glTF allows no more) is met once.
struct Instance {
  int node;
  int parent;  // index of the parent's Instance, -1 for a root
  glm::dmat4 world;
};

// A node's rest transform, checked: a matrix, or translation, rotation and scale.
RigNode rest_node(const Context& ctx, int index);

// The nodes of the default scene (or, without scenes, every node that is no node's child) and
// their descendants, parents before children. Iterative, so that a deep hierarchy cannot
// overflow the stack; a path longer than the node count means a cycle.
std::vector<Instance> traverse_nodes(const Context& ctx);

}  // namespace sst::gltf
