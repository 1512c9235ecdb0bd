// Parameters shared by the light-tree methods (slc, sst, rtslc, hybrid): the VPL set and the
// light tree built over it. Sampler-specific parameters live in the sampler's own struct and
// are appended by the registry entry, so this struct stays generic.
//
// The parameter tables are those of VplParams (vpl_generator.h) and LightTreeParams
// (light_tree.h).
#pragma once
#include "core/lighttree/light_tree.h"
#include "core/vpl/vpl_generator.h"

namespace sst {

// Where the node-distance floor starts to act (LightTreeParams::node_distance_floor_above), per
// kind of walk: forced on at every extent measured (results/README.md, 'Large extents'), it
// lowered the error of slc and sst, whose samples each walk the tree alone, from VPLs 2.9 view
// lengths wide on, and raised slc's at 2.1 (sst's fell 4% there); the cut methods rtslc and hybrid
// lost at 7.3 and 14.5 view lengths and gained from 145 on. The shared scenes' VPLs span 0.4-1.6
// view lengths: neither threshold acts there.
constexpr float kNodeFloorAboveForWalks = 2.5f;  // slc, sst
constexpr float kNodeFloorAboveForCuts = 50.0f;  // rtslc, hybrid

struct TreeMethodParams {
  VplParams vpl;
  LightTreeParams tree;

  // A method renders a view, so its tree's D is the view's (nothing outside it changes D); a tree
  // built without a camera can only take the VPLs' bounds.
  explicit TreeMethodParams(float node_distance_floor_above) {
    tree.sigma_max_relative_to = "view";
    tree.node_distance_floor_above = node_distance_floor_above;
  }

  template <class V>
  void visit(V&& v) {
    vpl.visit(v);
    tree.visit(v);
  }
};

}  // namespace sst
