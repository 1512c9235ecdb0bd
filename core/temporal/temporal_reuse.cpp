#include "core/temporal/temporal_reuse.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/filter/filters.h"
#include "core/util/error.h"

#define TEMPORAL_CTX_PARAM const ::sst::TemporalTexel *history,
#define TEMPORAL_HISTORY(i) (history[i])
#include "core/temporal/temporal_accumulate.h"

namespace sst {

void validate(const TemporalParams& p) {
  if (p.history_cap < 1) throw Error("history_cap must be >= 1 (got " + std::to_string(p.history_cap) + ")");
  if (!(p.depth_tolerance >= 0.0f) || !std::isfinite(p.depth_tolerance))
    throw Error("depth_tolerance must be finite and >= 0");
  if (!(p.normal_cos >= -1.0f && p.normal_cos <= 1.0f)) throw Error("normal_cos must be in [-1, 1]");
}

std::vector<TemporalInput> temporal_inputs(const Image& direct, const Image& indirect, const Image& albedo,
                                           const Image& depth, const Image& normal, const Image& motion,
                                           const Image& previous_depth) {
  std::vector<TemporalInput> in(direct.pixel_count());
  tbb::parallel_for(0, direct.height, [&](int y) {
    for (int x = 0; x < direct.width; ++x) {
      TemporalInput& t = in[size_t(y) * direct.width + x];
      t.direct = direct.rgb(x, y);
      t.indirect = indirect.rgb(x, y);
      t.albedo = albedo.rgb(x, y);
      t.depth = depth.at(x, y, 0);
      t.previous_depth = previous_depth.at(x, y, 0);
      t.normal = normal.rgb(x, y);
      t.motion = vec2(motion.at(x, y, 0), motion.at(x, y, 1));
      const vec3 divisor = albedo_divisor(t.albedo);
      t.luminance = vec2(luminance(t.direct / divisor), luminance(t.indirect / divisor));
      t.normal_change = 0.0f;
      if (t.depth > 0.0f) {
        const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
        for (int k = 0; k < 4; ++k) {
          const int qx = x + dx[k], qy = y + dy[k];
          if (qx < 0 || qy < 0 || qx >= direct.width || qy >= direct.height || !(depth.at(qx, qy, 0) > 0.0f)) continue;
          t.normal_change = std::max(t.normal_change, glm::length(normal.rgb(qx, qy) - t.normal));
        }
      }
      t.pad1 = 0.0f;
    }
  });
  return in;
}

TemporalPush temporal_push(const TemporalParams& params, int width, int height) {
  TemporalPush push{};
  push.width = uint32_t(width);
  push.height = uint32_t(height);
  push.history_cap = float(params.history_cap);
  push.depth_tolerance = params.depth_tolerance;
  push.normal_cos = params.normal_cos;
  return push;
}

std::vector<TemporalTexel> temporal_accumulate(const std::vector<TemporalInput>& input,
                                               const std::vector<TemporalTexel>& previous, const TemporalPush& push) {
  if (input.size() != size_t(push.width) * push.height) throw Error("temporal_accumulate: input size mismatch");
  // The first frame reads a history that matches nothing (depth 0), so it starts every average.
  std::vector<TemporalTexel> empty;
  if (previous.size() != input.size()) empty.assign(input.size(), TemporalTexel{});
  const std::vector<TemporalTexel>& history = previous.size() == input.size() ? previous : empty;
  std::vector<TemporalTexel> out(input.size());
  tbb::parallel_for(0, int(push.height), [&](int y) {
    for (int x = 0; x < int(push.width); ++x) {
      size_t i = size_t(y) * push.width + x;
      out[i] = temporal_accumulate_pixel(history.data(), x, y, input[i], push);
    }
  });
  return out;
}

TemporalImages temporal_images(const std::vector<TemporalTexel>& history, int width, int height) {
  TemporalImages out{Image(width, height, 3), Image(width, height, 3), Image(width, height, 3), Image(width, height, 2),
                     Image(width, height, 1)};
  tbb::parallel_for(size_t(0), history.size(), [&](size_t i) {
    const TemporalTexel& t = history[i];
    const vec3 divisor = albedo_divisor(t.albedo);
    for (int k = 0; k < 3; ++k) {
      out.direct.data[3 * i + k] = t.direct[k] / divisor[k];
      out.indirect.data[3 * i + k] = t.indirect[k] / divisor[k];
      out.albedo.data[3 * i + k] = t.albedo[k];
    }
    out.indirect_moments.data[2 * i] = t.moments.z;
    out.indirect_moments.data[2 * i + 1] = t.moments.w;
    out.frames.data[i] = t.frames;
  });
  return out;
}

void set_temporal_indirect(std::vector<TemporalTexel>& history, const Image& illumination, const Image& albedo) {
  if (history.size() != illumination.pixel_count() || history.size() != albedo.pixel_count())
    throw Error("set_temporal_indirect: size mismatch");
  tbb::parallel_for(size_t(0), history.size(), [&](size_t i) {
    const vec3 divisor = albedo_divisor(vec3(albedo.data[3 * i], albedo.data[3 * i + 1], albedo.data[3 * i + 2]));
    for (int k = 0; k < 3; ++k) history[i].indirect[k] = illumination.data[3 * i + k] * divisor[k];
  });
}

}  // namespace sst
