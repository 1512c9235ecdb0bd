#include "core/sampling/discrete_distribution.h"

#include <algorithm>
#include <cmath>

namespace sst {

DiscreteDistribution::DiscreteDistribution(const std::vector<double>& weights) {
  pmf_.resize(weights.size(), 0.0f);
  cdf_.resize(weights.size(), 0.0);
  double sum = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    double w = std::isfinite(weights[i]) && weights[i] > 0.0 ? weights[i] : 0.0;
    sum += w;
    cdf_[i] = sum;
  }
  total_ = sum;
  if (sum <= 0.0) return;
  for (size_t i = 0; i < weights.size(); ++i) {
    double prev = i ? cdf_[i - 1] : 0.0;
    pmf_[i] = float((cdf_[i] - prev) / sum);
  }
  for (double& c : cdf_) c /= sum;
  cdf_.back() = 1.0;
}

uint32_t DiscreteDistribution::sample(float u, float* u_remapped) const {
  // First index whose cdf exceeds u: skips zero-weight entries, whose cdf equals their
  // predecessor's.
  auto it = std::upper_bound(cdf_.begin(), cdf_.end(), double(u));
  size_t i = std::min<size_t>(size_t(it - cdf_.begin()), cdf_.size() - 1);
  while (i > 0 && pmf_[i] == 0.0f) --i;  // u rounding onto a trailing zero-weight entry
  if (u_remapped) {
    double lo = i ? cdf_[i - 1] : 0.0, width = cdf_[i] - lo;
    *u_remapped = width > 0.0 ? float(std::clamp((double(u) - lo) / width, 0.0, 0.99999994)) : 0.0f;
  }
  return uint32_t(i);
}

}  // namespace sst
