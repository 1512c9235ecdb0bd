// Helpers of the many-light method tests: small renders of the same frame by two methods, their
// layers, and the per-pixel z-test against an exact (exhaustive) image.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/manylight/many_light_methods.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/renderer.h"
#include "core/util/error.h"

namespace sst::test {

// The names of the VPL methods, from their list: the methods every test over "each VPL method"
// runs.
inline std::vector<std::string> many_light_method_names() {
  return {
#define ML_TEST_METHOD_NAME(name, id) #name,
      SST_MANY_LIGHT_METHODS(ML_TEST_METHOD_NAME)
#undef ML_TEST_METHOD_NAME
  };
}

// Whether method `method` has parameter `key`: tests pick the cases of a method by its parameters.
inline bool has_param(const std::string& method, const std::string& key) {
  for (const ParamInfo& p : find_method(method).params)
    if (p.name == key) return true;
  return false;
}

// Relative tolerance of a tree walk's float probability against the exact one computed in double
// from the same float weights: per level, the weights' sum, the division and the product each
// round once (2^-24 relative).
inline double walk_tolerance(const LightTree& tree) { return double(tree_height(tree) + 1) * 3.0 * 0x1p-24; }

// A small diffuse-only render of `method`, seed 3: renders with the same options jitter their
// camera rays identically, so an exhaustive render is the pixel-wise expectation of a sampler's.
inline RenderOptions small_options(const char* method, int spp, int width = 24, bool diffuse_only = true) {
  RenderOptions o;
  o.method = method;
  o.width = o.height = width;
  o.spp = spp;
  o.diffuse_only = diffuse_only;
  o.seed = 3;
  return o;
}

inline Image frame_layer(const RenderResult& r, const std::string& name) {
  for (const Layer& l : r.frame.layers())
    if (l.name == name) return l.image;
  ADD_FAILURE() << "no layer " << name;
  return {};
}

// Per-pixel z-test of `test` (with its variance of the mean) against a noiseless `expected`;
// the caller picks z_max Bonferroni-corrected for the number of pixel-channels (|z| < 5.1 is
// family-wise 1e-4 for ~3k of them). Returns the number of failures.
inline int z_test_failures(const Image& test, const Image& variance, const Image& expected, double z_max) {
  int failures = 0;
  for (size_t i = 0; i < test.data.size(); ++i) {
    double diff = double(test.data[i]) - double(expected.data[i]);
    double sd = std::sqrt(double(variance.data[i]));
    if (sd == 0.0 ? std::abs(diff) > 1e-6 * (1.0 + std::abs(expected.data[i])) : std::abs(diff) / sd > z_max) ++failures;
  }
  return failures;
}

// The message of the sst::Error that creating `method` with `params` throws, or "no error".
inline std::string create_method_error(const std::string& method, const nlohmann::json& params) {
  try {
    create_method(method, params);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace sst::test
