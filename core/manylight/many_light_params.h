// Parameters of the VPL methods that need nothing but VPLs (exhaustive, uniform): those of VPL
// generation (VplParams, vpl_generator.h).
#pragma once
#include "core/vpl/vpl_generator.h"

namespace sst {

struct VplMethodParams {
  VplParams vpl;
  template <class V>
  void visit(V&& v) {
    vpl.visit(v);
  }
};

}  // namespace sst
