// glTF animations as the neutral AnimationRig of animation.h: the channels read and checked
// (samplers, key times, output counts per interpolation, quaternions), the rig's nodes built from
// the instances that move, and the rig handed to the Scene. Apart from the loader because none of
// it is needed to load a still scene, and every rule of it is about keys, not geometry.
#pragma once
#include <vector>

#include "core/scene/animation.h"
#include "core/scene/gltf_accessors.h"
#include "core/scene/gltf_context.h"
#include "core/scene/gltf_nodes.h"

namespace sst::gltf {

// Every animation plays at once on one clock. A target animated by two animations follows the
// later one (glTF forbids two channels on one target only within an animation). Channels on
// morph target weights are ignored, as morph targets are. AnimationChannel::node is the glTF
// node here; build_rig_nodes maps it to the rig.
std::vector<AnimationChannel> read_animations(Context& ctx, const Accessors& accessors);

// The rig's nodes, added to `rig`: one RigNode per instance that a channel targets or that
// descends from one (a node instanced twice gets the channels twice), with the channels that
// target it. Returns, per instance, its rig node or -1.
std::vector<int> build_rig_nodes(const Context& ctx, const std::vector<Instance>& instances,
                                 std::vector<AnimationChannel> channels, AnimationRig& rig);

// Moves `rig` (its meshes, cameras and lights added by the loader) into scene.animation once the
// scene's geometry is final. Channels whose nodes are not in the rendered scene move nothing: no
// animation then.
void attach_animation(AnimationRig&& rig, Scene& scene);

}  // namespace sst::gltf
