#include "core/eval/svg_plot.h"

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

// Builds by appending: GCC 12 warns falsely (-Wrestrict) on chains that start with a literal.
std::string marker_shape(int shape, double cx, double cy, double r, const std::string& attrs) {
  std::string s = shape == 0 ? "<circle " : "<path ";
  s += attrs;
  if (shape == 0) {
    s.append(" cx=\"").append(num(cx)).append("\" cy=\"").append(num(cy)).append("\" r=\"").append(num(r));
    return s += '"';
  }
  // Square, triangle, diamond, inverted triangle: vertices in units of r, sized to look equal.
  static const std::vector<std::vector<std::pair<double, double>>> kVertices{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}},
                                                                             {{0, -1.2}, {1.1, 0.8}, {-1.1, 0.8}},
                                                                             {{0, -1.3}, {1.3, 0}, {0, 1.3}, {-1.3, 0}},
                                                                             {{0, 1.2}, {1.1, -0.8}, {-1.1, -0.8}}};
  s += " d=\"";
  const auto& vertices = kVertices[size_t(shape - 1) % kVertices.size()];
  for (size_t i = 0; i < vertices.size(); ++i)
    s.append(i ? "L" : "M")
        .append(num(cx + vertices[i].first * r))
        .append(",")
        .append(num(cy + vertices[i].second * r));
  return s += "Z\"";
}

std::string polyline(const std::vector<std::pair<double, double>>& xy, const std::string& style) {
  std::string s = "<polyline fill=\"none\" ";
  s.append(style).append(" points=\"");
  for (size_t i = 0; i < xy.size(); ++i)
    s.append(i ? " " : "").append(num(xy[i].first)).append(",").append(num(xy[i].second));
  return s += "\"/>\n";
}

std::string text(double x, double y, const std::string& anchor, const std::string& body,
                 const std::string& extra = "") {
  return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" text-anchor=\"" + anchor + "\"" + extra + ">" +
         xml_escape(body) + "</text>\n";
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

std::string grid_and_ticks(const PlotArea& f) {
  std::string s = "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (double t : f.x->ticks)
    s += "<line x1=\"" + num(f.px(t)) + "\" y1=\"" + num(f.top) + "\" x2=\"" + num(f.px(t)) + "\" y2=\"" +
         num(f.bottom) + "\"/>\n";
  for (double t : f.y->ticks)
    s += "<line x1=\"" + num(f.left) + "\" y1=\"" + num(f.py(t)) + "\" x2=\"" + num(f.right) + "\" y2=\"" +
         num(f.py(t)) + "\"/>\n";
  s += "</g>\n<rect x=\"" + num(f.left) + "\" y=\"" + num(f.top) + "\" width=\"" + num(f.right - f.left) +
       "\" height=\"" + num(f.bottom - f.top) +
       "\" fill=\"none\" stroke=\"#444\"/>\n<g class=\"ticks\" fill=\"#333\">\n";
  for (double t : labelled_ticks(
           *f.x, [&](double v) { return f.px(v); }, true))
    s += text(f.px(t), f.bottom + 16, "middle", format_tick(t));
  for (double t : labelled_ticks(
           *f.y, [&](double v) { return f.py(v); }, false))
    s += text(f.left - 6, f.py(t) + 4, "end", format_tick(t));
  return s + "</g>\n";
}

size_t style_of(const Plot& plot, size_t index) {
  const int style = plot.series[index].style;
  return style >= 0 ? size_t(style) : index;
}

std::string series_svg(const Plot& plot, const PlotArea& f, size_t index) {
  const PlotSeries& series = plot.series[index];
  const size_t style = style_of(plot, index);
  const std::string colour = kPalette[style % kPalette.size()];
  std::vector<std::pair<double, double>> xy;
  std::string markers;
  for (const PlotPoint& p : series.points) {
    if (!drawable(p, plot)) continue;
    xy.emplace_back(f.px(p.x), f.py(p.y));
    const std::string tip = series.name + ": " + format_tick(p.x) + ", " + format_tick(p.y);
    const std::string attrs = "class=\"marker\" fill=\"" + colour + "\" stroke=\"#fff\" stroke-width=\"0.8\"";
    markers += marker_shape(int(style % kShapes), xy.back().first, xy.back().second, 4.0, attrs) + "><title>" +
               xml_escape(tip) + "</title></" + (style % kShapes == 0 ? "circle" : "path") + ">\n";
  }
  std::string s = "<g class=\"series\">\n";
  if (series.line && xy.size() >= 2) s += polyline(xy, "stroke=\"" + colour + "\" stroke-width=\"1.5\"");
  return s + markers + "</g>\n";
}

std::string highlight_svg(const Plot& plot, const PlotArea& f) {
  std::vector<std::pair<double, double>> xy;
  for (const PlotPoint& p : plot.highlight.points)
    if (drawable(p, plot)) xy.emplace_back(f.px(p.x), f.py(p.y));
  if (xy.size() < 2) return "";
  return "<g class=\"highlight\">" + polyline(xy, "stroke=\"#000\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"") +
         "</g>\n";
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

std::string legend_svg(const Plot& plot, double x, double y) {
  std::string s = "<g class=\"legend\">\n";
  for (size_t i = 0; i < plot.series.size(); ++i, y += 18) {
    const size_t style = style_of(plot, i);
    const std::string colour = kPalette[style % kPalette.size()];
    if (plot.series[i].line) s += polyline({{x, y}, {x + 22, y}}, "stroke=\"" + colour + "\" stroke-width=\"1.5\"");
    s += marker_shape(int(style % kShapes), x + 11, y, 4.0, "class=\"legend-marker\" fill=\"" + colour + "\"") + "/>\n";
    s += text(x + 28, y + 4, "start", plot.series[i].name);
  }
  if (has_legend_highlight(plot)) {
    s += polyline({{x, y}, {x + 22, y}}, "stroke=\"#000\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"");
    s += text(x + 28, y + 4, "start", plot.highlight.name);
  }
  return s + "</g>\n";
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

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        // Control characters are not allowed in XML 1.0; a label never needs them.
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') ? ' ' : c;
    }
  }
  return out;
}

size_t drawable_point_count(const Plot& plot) {
  size_t n = 0;
  for (const PlotSeries& s : plot.series)
    n += size_t(std::count_if(s.points.begin(), s.points.end(), [&](const PlotPoint& p) { return drawable(p, plot); }));
  return n;
}

std::string render_svg(const Plot& plot) {
  const Axis x = axis_of(plot, true), y = axis_of(plot, false);
  const double legend = legend_width(plot);
  const PlotArea f{68.0, plot.title.empty() ? 14.0 : 34.0, plot.width - 16.0 - legend, plot.height - 46.0, &x, &y};
  const std::string w = std::to_string(plot.width), h = std::to_string(plot.height);
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"" + w + "\" height=\"" + h +
                  "\" viewBox=\"0 0 " + w + " " + h + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s += "<rect width=\"" + w + "\" height=\"" + h + "\" fill=\"#fff\"/>\n";
  if (!plot.title.empty())
    s += text((f.left + f.right) / 2, 20, "middle", plot.title, " font-size=\"14\" font-weight=\"bold\"");
  s += grid_and_ticks(f);
  s += text((f.left + f.right) / 2, plot.height - 10.0, "middle", plot.x.label);
  const double ly = (f.top + f.bottom) / 2;
  s += text(16, ly, "middle", plot.y.label, " transform=\"rotate(-90 16 " + num(ly) + ")\"");
  for (size_t i = 0; i < plot.series.size(); ++i) s += series_svg(plot, f, i);
  s += highlight_svg(plot, f);
  if (legend > 0) s += legend_svg(plot, f.right + 12, f.top + 8);
  return s + "</svg>\n";
}

}  // namespace sst
