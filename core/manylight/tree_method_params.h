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

struct TreeMethodParams {
  VplParams vpl;
  LightTreeParams tree;

  // A method renders a view, so its tree's D is the view's (nothing outside it changes D); a tree
  // built without a camera can only take the VPLs' bounds.
  TreeMethodParams() { tree.sigma_max_relative_to = "view"; }

  template <class V>
  void visit(V&& v) {
    vpl.visit(v);
    tree.visit(v);
  }
};

}  // namespace sst
