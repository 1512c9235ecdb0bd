#include "core/eval/plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>

namespace sst {
namespace {

// Tableau 10: distinguishable colours that stay readable printed in grey.
constexpr std::array<const char*, 10> kPalette{"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                               "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
constexpr int kShapes = 5;       // circle, square, triangle, diamond, inverted triangle
constexpr double kInset = 10.0;  // pixels between the plot border and the outermost data point

std::string num(double v, int decimals = 1) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

// m x 10^e, correctly rounded: dividing by an exact power of ten makes 3 x 10^-1 the double
// nearest 0.3, where 3 * 0.1 is not.
double decimal(double m, int e) { return e >= 0 ? m * std::pow(10.0, e) : m / std::pow(10.0, -e); }

bool near(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

bool drawable_value(double v, AxisScale scale) { return std::isfinite(v) && (scale == AxisScale::linear || v > 0.0); }

bool drawable(const PlotPoint& p, const Plot& plot) {
  return drawable_value(p.x, plot.x.scale) && drawable_value(p.y, plot.y.scale);
}

// The largest (round_up: smallest) 1, 2 or 5 x 10^k at or below (above) v > 0.
double round_125(double v, bool round_up) {
  const int k = int(std::floor(std::log10(v)));
  double best = round_up ? decimal(1, k + 2) : decimal(1, k - 1);
  for (int e = k - 1; e <= k + 1; ++e) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double c = decimal(m, e);
      if (round_up && c >= v * (1 - 1e-12) && c < best) best = c;
      if (!round_up && c <= v * (1 + 1e-12) && c > best) best = c;
    }
  }
  return best;
}

// An axis: its domain in data units (ends rounded outwards to nice values) and its ticks.
struct Axis {
  AxisScale scale = AxisScale::linear;
  double lo = 0.0, hi = 1.0;
  std::vector<double> ticks;

  double fraction(double v) const {
    if (scale == AxisScale::log10) return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    return (v - lo) / (hi - lo);
  }
};

Axis make_axis(double lo, double hi, AxisScale scale) {
  Axis a;
  a.scale = scale;
  if (lo > hi) {  // no drawable value: an empty but valid axis
    lo = scale == AxisScale::log10 ? 1.0 : 0.0;
    hi = scale == AxisScale::log10 ? 10.0 : 1.0;
  }
  if (scale == AxisScale::log10) {
    // 4% of the span (at least 0.02 decades) each side, so that end points do not sit on the border.
    const double pad = std::pow(10.0, std::max(0.02, 0.04 * std::log10(hi / lo)));
    a.lo = lo / pad;
    a.hi = hi * pad;
    a.ticks = log_ticks(a.lo, a.hi);
    if (a.ticks.size() < 2) {  // too narrow for two ticks: widen to nice ends, which are ticks
      a.lo = round_125(lo, false);
      a.hi = round_125(hi, true);
      a.ticks = log_ticks(a.lo, a.hi);
    }
  } else {
    a.ticks = linear_ticks(lo, hi);
    a.lo = a.ticks.front();
    a.hi = a.ticks.back();
  }
  return a;
}

Axis axis_of(const Plot& plot, bool is_x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto take = [&](const PlotSeries& s) {
    for (const PlotPoint& p : s.points) {
      if (!drawable(p, plot)) continue;
      lo = std::min(lo, is_x ? p.x : p.y);
      hi = std::max(hi, is_x ? p.x : p.y);
    }
  };
  for (const PlotSeries& s : plot.series) take(s);
  take(plot.highlight);
  return make_axis(lo, hi, is_x ? plot.x.scale : plot.y.scale);
}

// Pixel geometry of the plot area; data are mapped kInset pixels inside its border.
struct PlotArea {
  double left, top, right, bottom;
  const Axis* x;
  const Axis* y;
  double px(double v) const { return left + kInset + x->fraction(v) * (right - left - 2 * kInset); }
  double py(double v) const { return bottom - kInset - y->fraction(v) * (bottom - top - 2 * kInset); }
};

// Pixel positions to 0.1 px: finer than a screen shows, and short in the page.
double pixel(double v) { return std::round(v * 10.0) / 10.0; }

using nlohmann::json;

// A marker's position and shape: shape 0 is a circle, the others a closed path.
json marker_view(int shape, double cx, double cy, double r) {
  json marker = {{"circle", shape == 0}, {"cx", pixel(cx)}, {"cy", pixel(cy)}, {"r", r}, {"d", nullptr}};
  if (shape == 0) return marker;
  // Square, triangle, diamond, inverted triangle: vertices in units of r, sized to look equal.
  static const std::vector<std::vector<std::pair<double, double>>> kVertices{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}},
                                                                             {{0, -1.2}, {1.1, 0.8}, {-1.1, 0.8}},
                                                                             {{0, -1.3}, {1.3, 0}, {0, 1.3}, {-1.3, 0}},
                                                                             {{0, 1.2}, {1.1, -0.8}, {-1.1, -0.8}}};
  std::string d;
  const auto& vertices = kVertices[size_t(shape - 1) % kVertices.size()];
  for (size_t i = 0; i < vertices.size(); ++i)
    d.append(i ? "L" : "M").append(num(cx + vertices[i].first * r)).append(",").append(num(cy + vertices[i].second * r));
  marker["d"] = d + "Z";
  return marker;
}

// An SVG polyline's points attribute.
std::string points_text(const std::vector<std::pair<double, double>>& xy) {
  std::string s;
  for (size_t i = 0; i < xy.size(); ++i) s.append(i ? " " : "").append(num(xy[i].first)).append(",").append(num(xy[i].second));
  return s;
}

// The mantissa of v > 0 is one of `digits` (1 x 10^k, 2 x 10^k, ...).
bool has_mantissa(double v, std::initializer_list<double> digits) {
  const double m = v / decimal(1, int(std::floor(std::log10(v) + 1e-12)));
  return std::any_of(digits.begin(), digits.end(), [&](double d) { return std::abs(m - d) < 1e-6; });
}

// Labels that do not overlap: all ticks, else (log axes) those at 1, 2 and 5 x 10^k, else the
// powers of ten; the other ticks keep their grid lines. Text width is estimated (no renderer).
template <class ToPixel>
std::vector<double> labelled_ticks(const Axis& axis, ToPixel pixel, bool horizontal) {
  auto fits = [&](const std::vector<double>& ticks) {
    for (size_t i = 1; i < ticks.size(); ++i) {
      const double room = std::abs(pixel(ticks[i]) - pixel(ticks[i - 1]));
      const double need =
          horizontal ? 3.4 * double(format_tick(ticks[i]).size() + format_tick(ticks[i - 1]).size()) + 8 : 15.0;
      if (room < need) return false;
    }
    return true;
  };
  if (axis.scale == AxisScale::linear || fits(axis.ticks)) return axis.ticks;
  for (auto digits : {std::initializer_list<double>{1, 2, 5}, std::initializer_list<double>{1}}) {
    std::vector<double> some;
    std::copy_if(axis.ticks.begin(), axis.ticks.end(), std::back_inserter(some),
                 [&](double t) { return has_mantissa(t, digits); });
    if (some.size() >= 2 && fits(some)) return some;
  }
  return {axis.ticks.front(), axis.ticks.back()};
}

// An axis with its ticks: each at its pixel position along the axis, labelled unless labels
// would overlap, the label's anchor just outside the frame.
json axis_view(const PlotAxis& axis, const Axis& range, const PlotArea& f, bool is_x) {
  auto at = [&](double v) { return is_x ? f.px(v) : f.py(v); };
  const std::vector<double> labelled = labelled_ticks(range, at, is_x);
  json ticks = json::array();
  for (double t : range.ticks) {
    const bool has_label = std::find(labelled.begin(), labelled.end(), t) != labelled.end();
    ticks.push_back({{"value", t},
                     {"at", pixel(at(t))},
                     {"label", has_label ? json(format_tick(t)) : json(nullptr)},
                     {"label_x", pixel(is_x ? at(t) : f.left - 6)},
                     {"label_y", pixel(is_x ? f.bottom + 16 : at(t) + 4)}});
  }
  return {{"label", axis.label},
          {"scale", range.scale == AxisScale::log10 ? "log10" : "linear"},
          {"lo", range.lo},
          {"hi", range.hi},
          {"ticks", ticks},
          // The axis label: centred under the frame, or rotated beside it.
          {"label_x", pixel(is_x ? (f.left + f.right) / 2 : 16.0)},
          {"label_y", pixel(is_x ? f.bottom + 36 : (f.top + f.bottom) / 2)}};
}

size_t style_of(const Plot& plot, size_t index) {
  const int style = plot.series[index].style;
  return style >= 0 ? size_t(style) : index;
}

const char* colour_of(size_t style) { return kPalette[style % kPalette.size()]; }

json series_view(const Plot& plot, const PlotArea& f, size_t index) {
  const PlotSeries& series = plot.series[index];
  const size_t style = style_of(plot, index);
  std::vector<std::pair<double, double>> xy;
  json markers = json::array();
  for (const PlotPoint& p : series.points) {
    if (!drawable(p, plot)) continue;
    xy.emplace_back(f.px(p.x), f.py(p.y));
    json marker = marker_view(int(style % kShapes), xy.back().first, xy.back().second, 4.0);
    marker["x"] = p.x;
    marker["y"] = p.y;
    marker["tip"] = series.name + ": " + format_tick(p.x) + ", " + format_tick(p.y);
    markers.push_back(std::move(marker));
  }
  const bool line = series.line && xy.size() >= 2;
  return {{"name", series.name},
          {"colour", colour_of(style)},
          {"line", line ? json(points_text(xy)) : json(nullptr)},
          {"markers", markers}};
}

json highlight_view(const Plot& plot, const PlotArea& f) {
  std::vector<std::pair<double, double>> xy;
  for (const PlotPoint& p : plot.highlight.points)
    if (drawable(p, plot)) xy.emplace_back(f.px(p.x), f.py(p.y));
  if (xy.size() < 2) return nullptr;
  return {{"name", plot.highlight.name}, {"line", points_text(xy)}};
}

bool has_legend_highlight(const Plot& plot) {
  return !plot.highlight.name.empty() && plot.highlight.points.size() >= 2;
}

// Legend width from a rough average glyph width: SVG cannot measure text without a renderer.
double legend_width(const Plot& plot) {
  size_t longest = 0;
  for (const PlotSeries& s : plot.series) longest = std::max(longest, s.name.size());
  if (has_legend_highlight(plot)) longest = std::max(longest, plot.highlight.name.size());
  if (longest == 0) return 0.0;
  return std::min(34.0 + 6.8 * double(longest), plot.width * 0.45);
}

// An entry per series, then the highlight's; each a line sample and/or a marker, and the name.
json legend_view(const Plot& plot, double x, double y) {
  auto entry = [&](const std::string& name, const char* colour, bool line, bool dashed, json marker) {
    return json{{"name", name},
                {"colour", colour},
                {"line", line ? json(points_text({{x, y}, {x + 22, y}})) : json(nullptr)},
                {"dashed", dashed},
                {"marker", std::move(marker)},
                {"text_x", pixel(x + 28)},
                {"text_y", pixel(y + 4)}};
  };
  json entries = json::array();
  for (size_t i = 0; i < plot.series.size(); ++i, y += 18) {
    const size_t style = style_of(plot, i);
    entries.push_back(entry(plot.series[i].name, colour_of(style), plot.series[i].line, false,
                            marker_view(int(style % kShapes), x + 11, y, 4.0)));
  }
  if (has_legend_highlight(plot)) entries.push_back(entry(plot.highlight.name, "#000", true, true, nullptr));
  return {{"entries", entries}};
}

std::string tidy_exponent(const std::string& s) {
  const size_t e = s.find('e');
  return s.substr(0, e + 1) + std::to_string(std::atoi(s.c_str() + e + 1));
}

}  // namespace

std::vector<double> linear_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) {  // one value: centre it in a small range
    const double pad = lo != 0.0 ? std::abs(lo) * 0.1 : 1.0;
    lo -= pad;
    hi += pad;
  }
  const double raw = (hi - lo) / std::max(1, target - 1);
  const int e = int(std::floor(std::log10(raw)));
  const double f = raw / std::pow(10.0, e);
  const double m = f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0;
  const double step = decimal(m, e);
  std::vector<double> ticks;
  // The 1e-9 (in steps) keeps rounding noise from adding a tick beyond a range end that is one.
  for (double k = std::floor(lo / step + 1e-9); k <= std::ceil(hi / step - 1e-9); ++k)
    ticks.push_back(decimal(k * m, e));
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  const std::vector<std::vector<double>> mantissas{{1}, {1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};
  for (const auto& set : mantissas) {
    ticks.clear();
    for (int e = int(std::floor(std::log10(lo))); e <= int(std::ceil(std::log10(hi))); ++e) {
      for (double m : set) {
        const double t = decimal(m, e);
        if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9)) ticks.push_back(t);
      }
    }
    if (ticks.size() >= 3) return ticks;
  }
  if (ticks.size() >= 2) return ticks;
  // Less than a digit step wide: linear ticks inside the range.
  std::vector<double> inside;
  for (double t : linear_ticks(lo, hi))
    if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9) && t > 0.0) inside.push_back(t);
  return inside;
}

std::string format_tick(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (value == 0.0) return "0";
  const bool fixed = std::abs(value) >= 1e-4 && std::abs(value) < 1e6;
  char buf[64];
  for (int p = 0; p <= 15; ++p) {
    std::snprintf(buf, sizeof(buf), fixed ? "%.*f" : "%.*e", p, value);
    if (near(std::strtod(buf, nullptr), value) || (fixed && p >= 6) || (!fixed && p >= 5)) break;
  }
  return fixed ? std::string(buf) : tidy_exponent(buf);
}

size_t drawable_point_count(const Plot& plot) {
  size_t n = 0;
  for (const PlotSeries& s : plot.series)
    n += size_t(std::count_if(s.points.begin(), s.points.end(), [&](const PlotPoint& p) { return drawable(p, plot); }));
  return n;
}

json plot_view(const Plot& plot) {
  const Axis x = axis_of(plot, true), y = axis_of(plot, false);
  const double legend = legend_width(plot);
  const PlotArea f{68.0, plot.title.empty() ? 14.0 : 34.0, plot.width - 16.0 - legend, plot.height - 46.0, &x, &y};
  json series = json::array();
  for (size_t i = 0; i < plot.series.size(); ++i) series.push_back(series_view(plot, f, i));
  return {{"title", plot.title.empty() ? json(nullptr) : json(plot.title)},
          {"title_x", pixel((f.left + f.right) / 2)},
          {"width", plot.width},
          {"height", plot.height},
          {"frame",
           {{"left", pixel(f.left)},
            {"top", pixel(f.top)},
            {"right", pixel(f.right)},
            {"bottom", pixel(f.bottom)},
            {"width", pixel(f.right - f.left)},
            {"height", pixel(f.bottom - f.top)}}},
          {"x_axis", axis_view(plot.x, x, f, true)},
          {"y_axis", axis_view(plot.y, y, f, false)},
          {"series", series},
          {"highlight", highlight_view(plot, f)},
          {"legend", legend > 0 ? legend_view(plot, f.right + 12, f.top + 8) : json(nullptr)}};
}

Plot per_frame_plot(std::string title, PlotAxis y, const std::vector<FrameSeries>& series, int first_frame) {
  Plot plot;
  plot.title = std::move(title);
  plot.x = {"frame", AxisScale::linear};
  plot.y = std::move(y);
  for (const FrameSeries& s : series) {
    PlotSeries line{s.name, {}, true, s.style};
    for (size_t i = 0; i < s.values.size(); ++i) line.points.push_back({double(first_frame) + double(i), s.values[i]});
    plot.series.push_back(std::move(line));
  }
  return plot;
}

}  // namespace sst
