// Sampling an index in proportion to non-negative weights (lights by power, emissive triangles by
// area x radiance). An inverted CDF: O(log n) per sample, exact pmf for MIS and for tests.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sst {

class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  // Negative or non-finite weights count as 0. All-zero weights give an empty distribution.
  explicit DiscreteDistribution(const std::vector<double>& weights);

  bool empty() const { return total_ <= 0.0; }
  size_t size() const { return pmf_.size(); }
  // Index for u in [0,1); only indices with non-zero weight are ever returned. When
  // `u_remapped` is given it receives u's position within the chosen index's share of [0,1),
  // itself uniform, so a stratified u keeps stratifying what is sampled next.
  uint32_t sample(float u, float* u_remapped = nullptr) const;
  float pmf(uint32_t i) const { return i < pmf_.size() ? pmf_[i] : 0.0f; }
  double total() const { return total_; }
  // The tables themselves, for packing them for the GPU (gpu/light_upload.h).
  const std::vector<double>& cdf() const { return cdf_; }
  const std::vector<float>& pmfs() const { return pmf_; }

 private:
  std::vector<double> cdf_;  // cdf_[i] = sum of pmf over [0, i]; cdf_.back() == 1
  std::vector<float> pmf_;
  double total_ = 0.0;
};

}  // namespace sst
