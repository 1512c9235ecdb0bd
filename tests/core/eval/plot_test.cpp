#include "core/eval/plot.h"

#include "core/eval/page_template.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace sst {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

size_t count(const std::string& haystack, const std::string& needle) {
  size_t n = 0;
  for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + 1)) ++n;
  return n;
}

size_t marker_count(const nlohmann::json& view) {
  size_t n = 0;
  for (const nlohmann::json& s : view["series"]) n += s["markers"].size();
  return n;
}

// The labels an axis shows, in order.
std::vector<std::string> tick_labels(const nlohmann::json& axis) {
  std::vector<std::string> out;
  for (const nlohmann::json& t : axis["ticks"])
    if (t["label"].is_string()) out.push_back(t["label"]);
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

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

TEST(Plot, OneMarkerPerFinitePoint) {
  Plot plot = one_series({{1, 2}, {2, kNaN}, {kInf, 3}, {3, 4}, {4, 1}});
  plot.series.push_back({"b", {{0.5, 0.5}, {-kInf, 1}}, false});
  const nlohmann::json view = plot_view(plot);
  EXPECT_EQ(marker_count(view), 4u);
  EXPECT_EQ(drawable_point_count(plot), 4u);
  EXPECT_EQ(view.dump().find("nan"), std::string::npos);
  EXPECT_EQ(view.dump().find("inf"), std::string::npos);
  EXPECT_EQ(view["series"][0]["markers"][2]["x"], 4);
}

TEST(Plot, LogAxesSkipNonPositiveValues) {
  Plot plot = one_series({{0, 1}, {-1, 1}, {10, 1}, {100, 2}, {1000, 0}}, AxisScale::log10, AxisScale::log10);
  EXPECT_EQ(drawable_point_count(plot), 2u);
  EXPECT_EQ(marker_count(plot_view(plot)), 2u);
  plot.x.scale = AxisScale::linear;
  plot.y.scale = AxisScale::linear;
  EXPECT_EQ(drawable_point_count(plot), 5u);
  EXPECT_EQ(marker_count(plot_view(plot)), 5u);
}

TEST(Plot, LinearTicksAreNiceAndCoverTheRange) {
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

TEST(Plot, LogTicksArePowersOfTenThenOneTwoFive) {
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

TEST(Plot, LogAxisLabelsAreNiceNumbers) {
  const nlohmann::json view = plot_view(one_series({{3, 0.021}, {700, 0.078}}, AxisScale::log10, AxisScale::log10));
  for (const char* axis : {"x_axis", "y_axis"}) {
    const std::vector<std::string> labels = tick_labels(view[axis]);
    EXPECT_GE(labels.size(), 3u) << axis;
    for (const std::string& label : labels) EXPECT_TRUE(is_nice(std::stod(label), {1, 2, 3, 4, 5, 6, 7, 8, 9})) << label;
  }
}

TEST(Plot, LogAxisHugsTheDataRange) {
  // 97..376 ms: ticks 100, 200, 300 (not a 50..500 axis with the data in its middle).
  const nlohmann::json x = plot_view(one_series({{97, 1}, {376, 2}}, AxisScale::log10))["x_axis"];
  EXPECT_EQ(tick_labels(x), (std::vector<std::string>{"100", "200", "300"}));
  EXPECT_LT(x["lo"].get<double>(), 97);
  EXPECT_GT(x["lo"].get<double>(), 90);
}

TEST(Plot, CrowdedLogLabelsAreThinnedToOneTwoFive) {
  // 250..1060 on a narrow plot: ticks at every hundred, but 900 and 1000 would collide.
  Plot plot = one_series({{250, 1}, {1060, 2}}, AxisScale::log10);
  plot.width = 400;
  const nlohmann::json x = plot_view(plot)["x_axis"];
  const std::vector<std::string> labels = tick_labels(x);
  EXPECT_TRUE(has(labels, "500"));
  EXPECT_TRUE(has(labels, "1000"));
  EXPECT_FALSE(has(labels, "900"));
  EXPECT_FALSE(has(labels, "300"));
  // Every tick keeps its grid line: 300..1000.
  EXPECT_EQ(x["ticks"].size(), 8u);
}

TEST(Plot, StyleKeepsAColourWhateverTheSeriesPosition) {
  Plot plot = one_series({{1, 1}, {2, 2}});
  plot.series[0].style = 2;
  const nlohmann::json view = plot_view(plot);
  EXPECT_EQ(view["series"][0]["colour"], "#e15759");  // palette entry 2, not entry 0
  EXPECT_EQ(view["series"][0]["markers"][0]["circle"], false);  // shape 2: a triangle
  EXPECT_EQ(view["legend"]["entries"][0]["colour"], "#e15759");
}

TEST(Plot, FormatTickIsShort) {
  EXPECT_EQ(format_tick(3 * 0.1), "0.3");
  EXPECT_EQ(format_tick(0), "0");
  EXPECT_EQ(format_tick(1000), "1000");
  EXPECT_EQ(format_tick(-2.5), "-2.5");
  EXPECT_EQ(format_tick(1e-6), "1e-6");
  EXPECT_EQ(format_tick(2.5e7), "2.5e7");
  EXPECT_EQ(format_tick(0.0005), "0.0005");
}

TEST(Plot, MarkersLieInsideTheFrameInXOrder) {
  Plot plot = one_series({{1, 5}, {2, 7}, {4, 6}, {8, 9}});
  plot.width = 500;
  plot.height = 300;
  const nlohmann::json view = plot_view(plot);
  const nlohmann::json& frame = view["frame"];
  const nlohmann::json& m = view["series"][0]["markers"];
  ASSERT_EQ(m.size(), 4u);
  for (size_t i = 0; i < m.size(); ++i) {
    EXPECT_GT(m[i]["cx"], frame["left"]);
    EXPECT_LT(m[i]["cx"], frame["right"]);
    EXPECT_GT(m[i]["cy"], frame["top"]);
    EXPECT_LT(m[i]["cy"], frame["bottom"]);
    if (i) {
      EXPECT_GT(m[i]["cx"], m[i - 1]["cx"]);
    }
  }
  EXPECT_LT(m[3]["cy"], m[0]["cy"]);  // larger y is higher on the page
  EXPECT_LT(m[1]["cy"], m[2]["cy"]);
  EXPECT_LT(frame["right"].get<double>(), 500);
  EXPECT_LT(frame["bottom"].get<double>(), 300);
}

TEST(Plot, HighlightIsADashedPolylineInTheLegend) {
  Plot plot = one_series({{1, 3}, {2, 2}, {3, 1}});
  plot.highlight = {"Pareto front", {{1, 3}, {3, 1}}, true};
  nlohmann::json view = plot_view(plot);
  ASSERT_TRUE(view["highlight"].is_object());
  EXPECT_EQ(count(view["highlight"]["line"], ","), 2u);  // two points
  ASSERT_EQ(view["legend"]["entries"].size(), 2u);
  const nlohmann::json& entry = view["legend"]["entries"][1];
  EXPECT_EQ(entry["name"], "Pareto front");
  EXPECT_EQ(entry["dashed"], true);
  EXPECT_TRUE(entry["marker"].is_null());
  EXPECT_EQ(marker_count(view), 3u);  // the highlight adds no markers
  plot.highlight.points.resize(1);
  view = plot_view(plot);
  EXPECT_TRUE(view["highlight"].is_null());
  EXPECT_EQ(view["legend"]["entries"].size(), 1u);
}

TEST(Plot, LegendNamesEverySeriesWithItsOwnColourAndShape) {
  Plot plot = one_series({{1, 1}, {2, 2}});
  plot.series.push_back({"b", {{1, 2}}, true});
  plot.series.push_back({"c", {{2, 1}}, false});
  const nlohmann::json view = plot_view(plot);
  const nlohmann::json& entries = view["legend"]["entries"];
  ASSERT_EQ(entries.size(), 3u);
  std::set<std::string> colours;
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(entries[i]["name"], std::string(1, char('a' + i)));
    EXPECT_EQ(entries[i]["colour"], view["series"][i]["colour"]);
    colours.insert(entries[i]["colour"].get<std::string>());
  }
  EXPECT_EQ(colours.size(), 3u);
  EXPECT_EQ(entries[0]["marker"]["circle"], true);
  EXPECT_EQ(entries[1]["marker"]["circle"], false);
  EXPECT_TRUE(entries[1]["marker"]["d"].get<std::string>().starts_with("M"));
  // Lines: series a only (b has one point, c none asked for); legend samples for a and b.
  EXPECT_TRUE(view["series"][0]["line"].is_string());
  EXPECT_TRUE(view["series"][1]["line"].is_null());
  EXPECT_TRUE(view["series"][2]["line"].is_null());
  EXPECT_TRUE(entries[1]["line"].is_string());
  EXPECT_TRUE(entries[2]["line"].is_null());
}

TEST(Plot, TemplateEscapesText) {
  Plot plot = one_series({{1, 1}, {2, 2}});
  plot.title = "<script>&\"'";
  plot.series[0].name = "a<b>";
  plot.x.label = "x & y";
  const nlohmann::json view = plot_view(plot);
  EXPECT_EQ(view["title"], "<script>&\"'");  // the view holds text as shown
  const std::string svg = render_page_template("plot.svg", view);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
  EXPECT_NE(svg.find("&lt;script&gt;&amp;&quot;&#39;"), std::string::npos);
  EXPECT_NE(svg.find("x &amp; y"), std::string::npos);
  EXPECT_EQ(html_escape("a\x01<"), "a &lt;");
}

TEST(Plot, EmptyPlotIsStillAPlot) {
  const nlohmann::json view = plot_view(Plot{});
  EXPECT_EQ(view["series"].size(), 0u);
  EXPECT_TRUE(view["legend"].is_null());
  EXPECT_GE(view["x_axis"]["ticks"].size(), 2u);
  const std::string svg = render_page_template("plot.svg", view);
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
}

TEST(Plot, RenderedSvgIsDeterministicAndBalanced) {
  Plot plot = one_series({{0.1, 10}, {0.5, 20}, {2, 15}}, AxisScale::log10);
  plot.series.push_back({"b", {{0.2, 5}, {1, 25}}, true});
  EXPECT_EQ(plot_view(plot), plot_view(plot));
  const std::string svg = render_page_template("plot.svg", plot_view(plot));
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "</svg>"), 1u);
  EXPECT_EQ(count(svg, "<g"), count(svg, "</g>"));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  EXPECT_EQ(count(svg, "<title>"), 5u);  // a hover tip per marker
  EXPECT_EQ(count(svg, "class=\"marker\""), 5u);
  EXPECT_EQ(count(svg, "class=\"legend-marker\""), 2u);
  EXPECT_EQ(svg.find("{{"), std::string::npos);
}

TEST(Plot, PerFramePlotHasASeriesPerMethodOverFrameIndices) {
  const Plot plot = per_frame_plot("RMSE per frame", {"RMSE", AxisScale::log10},
                                   {{"pt", {0.2, 0.18, 0.21, 0.19}, 0}, {"sst", {0.1, 0.12, kNaN, 0.09}, 2}}, 16);
  const nlohmann::json view = plot_view(plot);
  EXPECT_EQ(view["title"], "RMSE per frame");
  EXPECT_EQ(view["x_axis"]["label"], "frame");
  EXPECT_EQ(view["x_axis"]["scale"], "linear");
  EXPECT_EQ(view["y_axis"]["scale"], "log10");
  ASSERT_EQ(view["series"].size(), 2u);
  EXPECT_EQ(view["series"][0]["name"], "pt");
  EXPECT_EQ(view["series"][1]["colour"], "#e15759");  // style 2
  std::vector<double> frames;
  for (const nlohmann::json& m : view["series"][1]["markers"]) frames.push_back(m["x"]);
  EXPECT_EQ(frames, (std::vector<double>{16, 17, 19}));  // frame 18's value is not a number
  EXPECT_EQ(view["series"][0]["markers"][1]["y"], 0.18);
  EXPECT_TRUE(view["series"][0]["line"].is_string());
  EXPECT_LE(view["x_axis"]["lo"].get<double>(), 16);
  EXPECT_GE(view["x_axis"]["hi"].get<double>(), 19);
  EXPECT_EQ(view["legend"]["entries"].size(), 2u);
}

}  // namespace
}  // namespace sst
