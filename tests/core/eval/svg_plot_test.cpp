#include "core/eval/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <regex>

namespace sst {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

size_t count(const std::string& haystack, const std::string& needle) {
  size_t n = 0;
  for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + 1)) ++n;
  return n;
}

// The values of attribute `name` on every circle marker, in document order.
std::vector<double> circle_attr(const std::string& svg, const std::string& name) {
  std::vector<double> out;
  const std::regex re("<circle class=\"marker\"[^>]* " + name + "=\"([-0-9.]+)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod((*it)[1]));
  return out;
}

Plot one_series(std::vector<PlotPoint> points, AxisScale x = AxisScale::linear, AxisScale y = AxisScale::linear) {
  Plot plot;
  plot.title = "t";
  plot.x = {"x", x};
  plot.y = {"y", y};
  plot.series.push_back({"a", std::move(points), true});
  return plot;
}

// True when v is k x 10^e for a mantissa k in `mantissas` (up to rounding).
bool is_nice(double v, std::initializer_list<double> mantissas) {
  if (v == 0.0) return true;
  const double e = std::floor(std::log10(std::abs(v)) + 1e-12);
  const double m = std::abs(v) / std::pow(10.0, e);
  for (double k : mantissas)
    if (std::abs(m - k) < 1e-9) return true;
  return false;
}

TEST(SvgPlot, OneMarkerPerFinitePoint) {
  Plot plot = one_series({{1, 2}, {2, kNaN}, {kInf, 3}, {3, 4}, {4, 1}});
  plot.series.push_back({"b", {{0.5, 0.5}, {-kInf, 1}}, false});
  const std::string svg = render_svg(plot);
  EXPECT_EQ(count(svg, "class=\"marker\""), 4u);
  EXPECT_EQ(drawable_point_count(plot), 4u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(SvgPlot, LogAxesSkipNonPositiveValues) {
  Plot plot = one_series({{0, 1}, {-1, 1}, {10, 1}, {100, 2}, {1000, 0}}, AxisScale::log10, AxisScale::log10);
  EXPECT_EQ(drawable_point_count(plot), 2u);
  EXPECT_EQ(count(render_svg(plot), "class=\"marker\""), 2u);
  plot.x.scale = AxisScale::linear;
  plot.y.scale = AxisScale::linear;
  EXPECT_EQ(drawable_point_count(plot), 5u);
}

TEST(SvgPlot, LinearTicksAreNiceAndCoverTheRange) {
  const std::vector<std::pair<double, double>> ranges{{0, 1},        {10, 50},   {0.013, 0.087}, {-3.2, 7.9},
                                                      {1234, 98765}, {0.3, 0.3}, {-5, -5},       {0, 0}};
  for (const auto& [lo, hi] : ranges) {
    const std::vector<double> t = linear_ticks(lo, hi);
    ASSERT_GE(t.size(), 3u) << lo << ".." << hi;
    EXPECT_LE(t.size(), 12u) << lo << ".." << hi;
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi);
    const double step = t[1] - t[0];
    EXPECT_TRUE(is_nice(step, {1, 2, 5})) << step;
    for (size_t i = 0; i < t.size(); ++i) {
      EXPECT_NEAR(t[i] / step, std::round(t[i] / step), 1e-9) << t[i];
      if (i) {
        EXPECT_NEAR(t[i] - t[i - 1], step, 1e-9 * step);
      }
    }
  }
  EXPECT_EQ(linear_ticks(10, 50), (std::vector<double>{10, 20, 30, 40, 50}));
  // Ticks are the doubles nearest their decimals, so their labels are short.
  for (double t : linear_ticks(0, 1)) EXPECT_LE(format_tick(t).size(), 3u) << t;
}

TEST(SvgPlot, LogTicksArePowersOfTenThenOneTwoFive) {
  EXPECT_EQ(log_ticks(1, 1000), (std::vector<double>{1, 10, 100, 1000}));
  EXPECT_EQ(log_ticks(0.02, 0.1), (std::vector<double>{0.02, 0.05, 0.1}));
  EXPECT_EQ(log_ticks(2, 5), (std::vector<double>{2, 3, 4, 5}));
  for (double t : log_ticks(3e-5, 0.2)) EXPECT_TRUE(is_nice(t, {1, 2, 5})) << t;
  // Narrower than one digit step: still at least two ticks, inside the range.
  const std::vector<double> narrow = log_ticks(0.0211, 0.0219);
  ASSERT_GE(narrow.size(), 2u);
  for (double t : narrow) {
    EXPECT_GE(t, 0.0211);
    EXPECT_LE(t, 0.0219);
  }
}

TEST(SvgPlot, LogAxisLabelsAreNiceNumbers) {
  const std::string svg = render_svg(one_series({{3, 0.021}, {700, 0.078}}, AxisScale::log10, AxisScale::log10));
  const std::regex re("<text [^>]*text-anchor=\"(middle|end)\">([^<]*)</text>");
  int labels = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it) {
    const std::string body = (*it)[2];
    if (body == "x" || body == "y" || body == "t") continue;  // axis labels and title
    ++labels;
    EXPECT_TRUE(is_nice(std::stod(body), {1, 2, 3, 4, 5, 6, 7, 8, 9})) << body;
  }
  EXPECT_GE(labels, 6);  // at least three ticks per axis
}

TEST(SvgPlot, LogAxisHugsTheDataRange) {
  // 97..376 ms: ticks 100, 200, 300 (not a 50..500 axis with the data in its middle).
  const std::string svg = render_svg(one_series({{97, 1}, {376, 2}}, AxisScale::log10));
  for (const char* label : {">100<", ">200<", ">300<"}) EXPECT_NE(svg.find(label), std::string::npos) << label;
  EXPECT_EQ(svg.find(">50<"), std::string::npos);
  EXPECT_EQ(svg.find(">500<"), std::string::npos);
}

TEST(SvgPlot, CrowdedLogLabelsAreThinnedToOneTwoFive) {
  // 250..1060 on a narrow plot: ticks at every hundred, but 900 and 1000 would collide.
  Plot plot = one_series({{250, 1}, {1060, 2}}, AxisScale::log10);
  plot.width = 400;
  const std::string svg = render_svg(plot);
  EXPECT_NE(svg.find(">500<"), std::string::npos);
  EXPECT_NE(svg.find(">1000<"), std::string::npos);
  EXPECT_EQ(svg.find(">900<"), std::string::npos);
  EXPECT_EQ(svg.find(">300<"), std::string::npos);
  // Every tick keeps its grid line: 8 vertical (300..1000) plus the horizontal ones.
  EXPECT_GE(count(svg, "<line "), 8u + 3u);
}

TEST(SvgPlot, StyleKeepsAColourWhateverTheSeriesPosition) {
  Plot plot = one_series({{1, 1}, {2, 2}});
  plot.series[0].style = 2;
  const std::string svg = render_svg(plot);
  EXPECT_NE(svg.find("class=\"marker\" fill=\"#e15759\""), std::string::npos);  // palette entry 2
  EXPECT_EQ(svg.find("#4e79a7"), std::string::npos);                            // not entry 0
}

TEST(SvgPlot, FormatTickIsShort) {
  EXPECT_EQ(format_tick(3 * 0.1), "0.3");
  EXPECT_EQ(format_tick(0), "0");
  EXPECT_EQ(format_tick(1000), "1000");
  EXPECT_EQ(format_tick(-2.5), "-2.5");
  EXPECT_EQ(format_tick(1e-6), "1e-6");
  EXPECT_EQ(format_tick(2.5e7), "2.5e7");
  EXPECT_EQ(format_tick(0.0005), "0.0005");
}

TEST(SvgPlot, MarkersLieInsideTheFrameInXOrder) {
  Plot plot = one_series({{1, 5}, {2, 7}, {4, 6}, {8, 9}});
  plot.width = 500;
  plot.height = 300;
  const std::string svg = render_svg(plot);
  const std::vector<double> cx = circle_attr(svg, "cx"), cy = circle_attr(svg, "cy");
  ASSERT_EQ(cx.size(), 4u);
  for (size_t i = 0; i < cx.size(); ++i) {
    EXPECT_GT(cx[i], 0);
    EXPECT_LT(cx[i], 500);
    EXPECT_GT(cy[i], 0);
    EXPECT_LT(cy[i], 300);
    if (i) {
      EXPECT_GT(cx[i], cx[i - 1]);
    }
  }
  EXPECT_LT(cy[3], cy[0]);  // larger y is higher on the page
  EXPECT_LT(cy[1], cy[2]);
}

TEST(SvgPlot, HighlightIsADashedPolylineInTheLegend) {
  Plot plot = one_series({{1, 3}, {2, 2}, {3, 1}});
  plot.highlight = {"Pareto front", {{1, 3}, {3, 1}}, true};
  std::string svg = render_svg(plot);
  EXPECT_EQ(count(svg, "stroke-dasharray"), 2u);  // the line and its legend sample
  EXPECT_NE(svg.find(">Pareto front</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "class=\"marker\""), 3u);  // the highlight adds no markers
  plot.highlight.points.resize(1);
  svg = render_svg(plot);
  EXPECT_EQ(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_EQ(svg.find("Pareto front"), std::string::npos);
}

TEST(SvgPlot, LegendNamesEverySeriesWithItsOwnColourAndShape) {
  Plot plot = one_series({{1, 1}, {2, 2}});
  plot.series.push_back({"b", {{1, 2}}, true});
  plot.series.push_back({"c", {{2, 1}}, false});
  const std::string svg = render_svg(plot);
  EXPECT_EQ(count(svg, "class=\"legend-marker\""), 3u);
  for (const char* name : {">a</text>", ">b</text>", ">c</text>"}) EXPECT_NE(svg.find(name), std::string::npos);
  EXPECT_NE(svg.find("<circle class=\"legend-marker\" fill=\"#4e79a7\""), std::string::npos);
  EXPECT_NE(svg.find("<path class=\"legend-marker\" fill=\"#f28e2b\""), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 1u + 2u);  // series a's line, legend lines of a and b
}

TEST(SvgPlot, EscapesText) {
  Plot plot = one_series({{1, 1}, {2, 2}});
  plot.title = "<script>&\"'";
  plot.series[0].name = "a<b>";
  plot.x.label = "x & y";
  const std::string svg = render_svg(plot);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
  EXPECT_NE(svg.find("&lt;script&gt;&amp;&quot;&#39;"), std::string::npos);
  EXPECT_NE(svg.find("x &amp; y"), std::string::npos);
  EXPECT_EQ(xml_escape("a\x01<"), "a &lt;");
}

TEST(SvgPlot, EmptyPlotIsStillAnSvg) {
  const std::string svg = render_svg(Plot{});
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
  EXPECT_EQ(count(svg, "class=\"marker\""), 0u);
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
}

TEST(SvgPlot, OutputIsDeterministicAndBalanced) {
  Plot plot = one_series({{0.1, 10}, {0.5, 20}, {2, 15}}, AxisScale::log10);
  plot.series.push_back({"b", {{0.2, 5}, {1, 25}}, true});
  const std::string svg = render_svg(plot);
  EXPECT_EQ(svg, render_svg(plot));
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "</svg>"), 1u);
  EXPECT_EQ(count(svg, "<g"), count(svg, "</g>"));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  EXPECT_EQ(count(svg, "<title>"), 5u);  // a hover tip per marker
}

}  // namespace
}  // namespace sst
