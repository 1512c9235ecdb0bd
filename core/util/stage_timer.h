// Per-stage wall times of one run, in the order the stages ran (load, accel build, render, ...).
#pragma once
#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace sst {

class StageTimer {
 public:
  // Times the callable and records it under `stage` (accumulates if the stage repeats).
  template <class F>
  auto time(const std::string& stage, F&& f) {
    auto start = std::chrono::steady_clock::now();
    struct Record {
      StageTimer* self;
      const std::string& stage;
      std::chrono::steady_clock::time_point start;
      ~Record() {
        self->add(stage, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      }
    } record{this, stage, start};
    return f();
  }
  void add(const std::string& stage, double ms);
  double ms(const std::string& stage) const;  // 0 when the stage never ran
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }

 private:
  std::vector<std::pair<std::string, double>> stages_;
};

}  // namespace sst
