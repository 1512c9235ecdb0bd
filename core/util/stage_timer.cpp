#include "core/util/stage_timer.h"

namespace sst {

void StageTimer::add(const std::string& stage, double ms) {
  for (auto& [name, total] : stages_)
    if (name == stage) {
      total += ms;
      return;
    }
  stages_.emplace_back(stage, ms);
}

double StageTimer::ms(const std::string& stage) const {
  for (const auto& [name, total] : stages_)
    if (name == stage) return total;
  return 0.0;
}

}  // namespace sst
