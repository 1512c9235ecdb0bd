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
// method: forced on at every extent measured (results/README.md, 'Large extents'), it lowered
// slc's error from VPLs 2.6 view lengths wide on and raised it at 2.1 and 2.5; it lowered sst's at
// every extent measured from 2.1 on (by 4% there, 10% at 2.5); the cut methods rtslc and hybrid
// lost at 7.3 and 14.5 view lengths and gained from 145 on. The shared scenes' VPLs span 0.4-1.6
// view lengths: no threshold acts there.
constexpr float kNodeFloorAboveForSlc = 2.5f;
constexpr float kNodeFloorAboveForSst = 2.0f;
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
