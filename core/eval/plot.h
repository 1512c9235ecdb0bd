// Line/scatter plots for the report, as data. plot_view() does all the arithmetic (axis ranges,
// ticks, every pixel position) and core/eval/report/plot.svg only draws what it is given: no
// plotting library is available offline, and inline SVG keeps report.html a single file that any
// browser shows. The view is a pure function of the Plot, so the same results give the same report.
#pragma once
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
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

// The plot's view model, the data plot.svg draws (keys in docs/sst-eval.md). Points with a
// non-finite coordinate, or a non-positive one on a log axis, are left out (not drawn, not counted
// in the axis range). Pixel positions are rounded to 0.1 px.
nlohmann::json plot_view(const Plot& plot);

// Points of all series (not the highlight) that plot_view draws.
size_t drawable_point_count(const Plot& plot);

// A value per frame for each of several series (e.g. RMSE per frame, one series per method).
struct FrameSeries {
  std::string name;
  std::vector<double> values;  // values[i] belongs to frame first_frame + i
  int style = -1;              // as PlotSeries::style
};

// x = frame index (linear), y = the values on `y`'s scale, one line with markers per series.
Plot per_frame_plot(std::string title, PlotAxis y, const std::vector<FrameSeries>& series, int first_frame = 0);

// Axis ticks, for tests and for plot_view. Linear: multiples of 1, 2 or 5 x 10^k covering
// [lo, hi] (about `target` of them, ends rounded outwards). Log: powers of ten in [lo, hi], with
// 2 and 5 (then every digit) x 10^k added while there are fewer than three; lo > 0. A log axis
// keeps the data range (padded a little) rather than rounding out to whole decades, which would
// squeeze data spanning half a decade into a corner.
std::vector<double> linear_ticks(double lo, double hi, int target = 5);
std::vector<double> log_ticks(double lo, double hi);

// A tick label: the shortest of up to 6 significant digits, e.g. 0.3 not 0.30000000000000004.
std::string format_tick(double value);

}  // namespace sst
