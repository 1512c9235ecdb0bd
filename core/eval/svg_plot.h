// A small SVG line/scatter plot writer for the report: no plotting library is available offline,
// and inline SVG keeps report.html a single file that any browser shows. Output is a pure
// function of the Plot, so the same results give the same report bytes.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sst {

struct PlotPoint {
  double x = 0.0;
  double y = 0.0;
};

struct PlotSeries {
  std::string name;
  std::vector<PlotPoint> points;
  bool line = true;  // join the drawable points, in the given order, with a polyline
  // Colour and marker shape, cycling through a fixed palette; -1: the series' position. Lets a
  // caller keep one colour per method across several plots.
  int style = -1;
};

enum class AxisScale { linear, log10 };

struct PlotAxis {
  std::string label;
  AxisScale scale = AxisScale::linear;
};

struct Plot {
  std::string title;
  PlotAxis x;
  PlotAxis y;
  std::vector<PlotSeries> series;  // each: its own colour and marker shape, and a legend entry
  // Drawn over the series as a dashed black polyline without markers (the Pareto front). Named in
  // the legend when its name is not empty; nothing is drawn when it has fewer than 2 points.
  PlotSeries highlight;
  int width = 640;  // SVG size in pixels; the legend takes its room from the right
  int height = 400;
};

// The <svg> element. Points with a non-finite coordinate, or a non-positive one on a log axis,
// are skipped (not drawn, not counted in the axis range). Every drawn marker has class="marker".
std::string render_svg(const Plot& plot);

// Points of all series (not the highlight) that render_svg would draw.
size_t drawable_point_count(const Plot& plot);

// Axis ticks, for tests and for render_svg. Linear: multiples of 1, 2 or 5 x 10^k covering
// [lo, hi] (about `target` of them, ends rounded outwards). Log: powers of ten in [lo, hi], with
// 2 and 5 (then every digit) x 10^k added while there are fewer than three; lo > 0. A log axis
// keeps the data range (padded a little) rather than rounding out to whole decades, which would
// squeeze data spanning half a decade into a corner.
std::vector<double> linear_ticks(double lo, double hi, int target = 5);
std::vector<double> log_ticks(double lo, double hi);

// A tick label: the shortest of up to 6 significant digits, e.g. 0.3 not 0.30000000000000004.
std::string format_tick(double value);

// &, <, >, " and ' as entities: safe in XML/HTML text and attribute values.
std::string xml_escape(std::string_view text);

}  // namespace sst
