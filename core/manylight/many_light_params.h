// Parameters of the VPL methods that need nothing but VPLs (exhaustive, uniform).
//
// | parameter        | default | meaning                                                       |
// |------------------|---------|---------------------------------------------------------------|
// | vpls             | 100000  | number of VPLs deposited (see vpl_generator.h)                |
// | vpl_max_bounces  | 8       | surface hits per light path that deposit a VPL                |
// | vpl_min_bounces  | 3       | light-path hits before Russian roulette                       |
// | clamp_fraction   | 0.01    | singularity clamp, fraction of the VPL-bounds diagonal        |
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
