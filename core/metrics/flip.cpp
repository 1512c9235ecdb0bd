#include "core/metrics/flip.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/metrics/same_shape.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

namespace sst {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The colour-difference remapping (HPG 2020, section 4.1) and the feature exponent (section 4.2).
constexpr double kQc = 0.7;
constexpr double kPc = 0.4;
constexpr double kPt = 0.95;
constexpr double kQf = 0.5;
static_assert(kQf == 0.5, "ldr_map takes the feature difference's square root");
// Width of the feature detectors' Gaussian in degrees of visual angle: sigma = 0.5 w ppd.
constexpr double kFeatureWidthDeg = 0.082;

// A contrast sensitivity function in the spatial domain, a sum of two Gaussians of the distance
// r in degrees: a1 sqrt(pi/b1) exp(-pi^2 r^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2/b2).
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kCsfAchromatic{1.0, 0.0047, 0.0, 1.0e-5};
constexpr Csf kCsfRedGreen{1.0, 0.0053, 0.0, 1.0e-5};
constexpr Csf kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};
// One Gaussian each: their filters are one outer product of 1D filters, the blue-yellow one two.
static_assert(kCsfAchromatic.a2 == 0.0 && kCsfRedGreen.a2 == 0.0);

// The contrast sensitivity filters cover 3 standard deviations of their widest Gaussian.
int csf_radius(double ppd) {
  const double b_max = std::max({kCsfAchromatic.b1, kCsfRedGreen.b1, kCsfBlueYellow.b1, kCsfAchromatic.b2,
                                 kCsfRedGreen.b2, kCsfBlueYellow.b2});
  return int(std::ceil(3.0 * std::sqrt(b_max / (2.0 * kPi * kPi)) * ppd));
}

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 inverse(const Mat3& m) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      c[j][i] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];  // the adjugate, transposed in place
    }
  const double det = m[0][0] * c[0][0] + m[0][1] * c[1][0] + m[0][2] * c[2][0];
  for (auto& row : c)
    for (double& v : row) v /= det;
  return c;
}

// Linear sRGB <-> CIE XYZ from the sRGB primaries and D65 (chromaticity to five digits), and
// the white those give, which CIELab and YCxCz are relative to.
struct ColourSpace {
  Mat3 to_xyz{}, from_xyz{};
  std::array<double, 3> white{};

  ColourSpace() {
    const double primaries[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    const double wx = 0.31271, wy = 0.32902;
    Mat3 p{};
    for (int k = 0; k < 3; ++k) {
      const double x = primaries[k][0], y = primaries[k][1];
      p[0][k] = x / y, p[1][k] = 1.0, p[2][k] = (1.0 - x - y) / y;
    }
    const std::array<double, 3> w = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
    const Mat3 pi = inverse(p);
    for (int k = 0; k < 3; ++k) {
      const double s = pi[k][0] * w[0] + pi[k][1] * w[1] + pi[k][2] * w[2];
      for (int i = 0; i < 3; ++i) to_xyz[i][k] = p[i][k] * s;
    }
    from_xyz = inverse(to_xyz);
    for (int i = 0; i < 3; ++i) white[i] = to_xyz[i][0] + to_xyz[i][1] + to_xyz[i][2];
  }
};

const ColourSpace& colour_space() {
  static const ColourSpace space;
  return space;
}

// CIELab's f(t): the cube root above (6/29)^3, its tangent line below.
template <class T>
T lab_f(T t) {
  constexpr T delta = T(6.0 / 29.0);
  return t > delta * delta * delta ? std::cbrt(t) : t / (T(3) * delta * delta) + T(4.0 / 29.0);
}

// CIELab of linear RGB with the Hunt adjustment (a and b scaled by 0.01 L: chroma is less
// visible in the dark).
template <class T>
std::array<T, 3> hunt_lab(const std::array<T, 3>& rgb) {
  const ColourSpace& cs = colour_space();
  std::array<T, 3> f;
  for (int i = 0; i < 3; ++i) {
    const T v = T(cs.to_xyz[i][0]) * rgb[0] + T(cs.to_xyz[i][1]) * rgb[1] + T(cs.to_xyz[i][2]) * rgb[2];
    f[i] = lab_f(v / T(cs.white[i]));
  }
  const T l = T(116) * f[1] - T(16);
  return {l, T(0.01) * l * T(500) * (f[0] - f[1]), T(0.01) * l * T(200) * (f[1] - f[2])};
}

// HyAB: city-block distance in lightness, Euclidean in the chromatic plane.
template <class T>
T hyab(const std::array<T, 3>& p, const std::array<T, 3>& q) {
  return std::abs(p[0] - q[0]) + std::sqrt((p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

// The largest colour difference (raised to qc): that of pure green and pure blue.
double max_colour_difference() {
  return std::pow(hyab(hunt_lab<double>({0.0, 1.0, 0.0}), hunt_lab<double>({0.0, 0.0, 1.0})), kQc);
}

// 1D filters, all of odd length; the 2D filters are their outer products (the blue-yellow one a
// sum of two such products), normalised as the paper normalises the 2D filters.
struct Filters {
  int csf_radius = 0;
  std::vector<float> achromatic, red_green, blue_yellow_1, blue_yellow_2;
  int feature_radius = 0;
  std::vector<float> gauss, d1, d2;  // Gaussian, its first and second derivatives
};

Filters make_filters(double ppd) {
  Filters f;
  f.csf_radius = csf_radius(ppd);
  const int n = 2 * f.csf_radius + 1;
  // The 1D factor of one Gaussian term: the square root of its 2D peak, so that the product of
  // two factors is the 2D term.
  auto term = [](double x2, double a, double b) {
    return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-kPi * kPi * x2 / b);
  };
  std::vector<double> ach(n), rg(n), by1(n), by2(n);
  double s_ach = 0, s_rg = 0, s_by1 = 0, s_by2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = (i - f.csf_radius) / ppd, x2 = x * x;
    ach[i] = term(x2, kCsfAchromatic.a1, kCsfAchromatic.b1);
    rg[i] = term(x2, kCsfRedGreen.a1, kCsfRedGreen.b1);
    by1[i] = term(x2, kCsfBlueYellow.a1, kCsfBlueYellow.b1);
    by2[i] = term(x2, kCsfBlueYellow.a2, kCsfBlueYellow.b2);
    s_ach += ach[i], s_rg += rg[i], s_by1 += by1[i], s_by2 += by2[i];
  }
  // The 2D sums: s^2 for one product, s1^2 + s2^2 for the blue-yellow sum of two.
  const double n_by = 1.0 / std::sqrt(s_by1 * s_by1 + s_by2 * s_by2);
  for (int i = 0; i < n; ++i) {
    f.achromatic.push_back(float(ach[i] / s_ach));
    f.red_green.push_back(float(rg[i] / s_rg));
    f.blue_yellow_1.push_back(float(by1[i] * n_by));
    f.blue_yellow_2.push_back(float(by2[i] * n_by));
  }

  const double sigma = 0.5 * kFeatureWidthDeg * ppd;
  f.feature_radius = int(std::ceil(3.0 * sigma));
  const int m = 2 * f.feature_radius + 1;
  std::vector<double> g(m), d1(m), d2(m);
  double g_sum = 0, d1_pos = 0, d1_neg = 0, d2_pos = 0, d2_neg = 0;
  for (int i = 0; i < m; ++i) {
    const double x = i - f.feature_radius;
    g[i] = std::exp(-x * x / (2.0 * sigma * sigma));
    d1[i] = -x / (sigma * sigma) * g[i];
    d2[i] = (x * x / (sigma * sigma) - 1.0) / (sigma * sigma) * g[i];
    g_sum += g[i];
    (d1[i] > 0 ? d1_pos : d1_neg) += std::abs(d1[i]);
    (d2[i] > 0 ? d2_pos : d2_neg) += std::abs(d2[i]);
  }
  // The Gaussian sums to 1; each derivative's positive weights to 1 and its negative ones to -1.
  for (int i = 0; i < m; ++i) {
    f.gauss.push_back(float(g[i] / g_sum));
    f.d1.push_back(float(d1[i] / (d1[i] > 0 ? d1_pos : d1_neg)));
    f.d2.push_back(float(d2[i] / (d2[i] > 0 ? d2_pos : d2_neg)));
  }
  return f;
}

using Plane = std::vector<float>;

// Rows [y0, y1) of `in` (width w) convolved horizontally with each filter of `taps`, borders
// clamped to the edge pixel.
template <size_t N>
void filter_rows(const Plane& in, int w, int y0, int y1, const std::array<const std::vector<float>*, N>& taps,
                 int radius, const std::array<Plane*, N>& out) {
  std::vector<float> padded(size_t(w) + 2 * radius);
  for (int y = y0; y < y1; ++y) {
    const float* row = &in[size_t(y) * w];
    for (int i = 0; i < int(padded.size()); ++i) padded[i] = row[std::clamp(i - radius, 0, w - 1)];
    for (size_t k = 0; k < N; ++k) {
      const float* t = taps[k]->data();
      float* o = &(*out[k])[size_t(y) * w];
      // Tap outermost, x innermost: the loop vectorises.
      std::fill(o, o + w, 0.0f);
      for (int j = 0; j <= 2 * radius; ++j) {
        const float tj = t[j];
        const float* in_j = padded.data() + j;
        for (int x = 0; x < w; ++x) o[x] += tj * in_j[x];
      }
    }
  }
}

// Row y of `in` (width w, height h) convolved vertically with `taps`, borders clamped, into out.
void filter_column(const Plane& in, int w, int h, int y, const std::vector<float>& taps, int radius, float* out) {
  std::fill(out, out + w, 0.0f);
  for (int j = 0; j <= 2 * radius; ++j) {
    const float* row = &in[size_t(std::clamp(y + j - radius, 0, h - 1)) * w];
    const float t = taps[j];
    for (int x = 0; x < w; ++x) out[x] += t * row[x];
  }
}

template <class F>
void for_rows(int h, F body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
}

// One image in opponent space: YCxCz (linearized CIELab: Y = 116 y - 16, Cx = 500 (x - y),
// Cz = 200 (y - z), x y z relative to the white), and its relative luminance y for the features.
struct Opponent {
  Plane y, cx, cz, luminance;
};

Opponent to_opponent(const Image& rgb) {
  const ColourSpace& cs = colour_space();
  const size_t n = rgb.pixel_count();
  Opponent o{Plane(n), Plane(n), Plane(n), Plane(n)};
  std::array<std::array<float, 3>, 3> m;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) m[i][k] = float(cs.to_xyz[i][k] / cs.white[i]);
  for (size_t p = 0; p < n; ++p) {
    const float r = rgb.data[p * 3], g = rgb.data[p * 3 + 1], b = rgb.data[p * 3 + 2];
    const float x = m[0][0] * r + m[0][1] * g + m[0][2] * b;
    const float y = m[1][0] * r + m[1][1] * g + m[1][2] * b;
    const float z = m[2][0] * r + m[2][1] * g + m[2][2] * b;
    o.y[p] = 116.0f * y - 16.0f;
    o.cx[p] = 500.0f * (x - y);
    o.cz[p] = 200.0f * (y - z);
    o.luminance[p] = y;
  }
  return o;
}

// Filtered YCxCz back to linear RGB, clamped to the displayable [0,1], as Hunt-adjusted CIELab.
std::array<float, 3> filtered_to_lab(float lightness, float cx, float cz) {
  const ColourSpace& cs = colour_space();
  const float y = (lightness + 16.0f) / 116.0f;
  const float xyz[3] = {float((y + cx / 500.0f) * cs.white[0]), float(y * cs.white[1]),
                        float((y - cz / 200.0f) * cs.white[2])};
  std::array<float, 3> rgb;
  for (int i = 0; i < 3; ++i)
    rgb[i] = std::clamp(float(cs.from_xyz[i][0]) * xyz[0] + float(cs.from_xyz[i][1]) * xyz[1] +
                            float(cs.from_xyz[i][2]) * xyz[2],
                        0.0f, 1.0f);
  return hunt_lab(rgb);
}

// LDR-FLIP of two linear RGB images already in [0,1]: the per-pixel map.
Plane ldr_map(const Image& test, const Image& reference, const Filters& f) {
  const int w = test.width, h = test.height;
  const size_t n = test.pixel_count();
  Plane out(n);
  if (n == 0) return out;
  const Opponent o[2] = {to_opponent(test), to_opponent(reference)};

  // Colour: each channel through its contrast sensitivity filter, horizontally then vertically.
  struct Horizontal {
    Plane y, cx, cz1, cz2;
  };
  Horizontal hz[2];
  for (Horizontal& hh : hz) hh = {Plane(n), Plane(n), Plane(n), Plane(n)};
  for (int i = 0; i < 2; ++i)
    for_rows(h, [&](int y0, int y1) {
      filter_rows<1>(o[i].y, w, y0, y1, {&f.achromatic}, f.csf_radius, {&hz[i].y});
      filter_rows<1>(o[i].cx, w, y0, y1, {&f.red_green}, f.csf_radius, {&hz[i].cx});
      filter_rows<2>(o[i].cz, w, y0, y1, {&f.blue_yellow_1, &f.blue_yellow_2}, f.csf_radius, {&hz[i].cz1, &hz[i].cz2});
    });
  // Features: the luminance through the Gaussian and its derivatives, horizontally.
  struct Features {
    Plane g, d1, d2;
  };
  Features fh[2];
  for (int i = 0; i < 2; ++i) {
    fh[i] = {Plane(n), Plane(n), Plane(n)};
    for_rows(h, [&](int y0, int y1) {
      filter_rows<3>(o[i].luminance, w, y0, y1, {&f.gauss, &f.d1, &f.d2}, f.feature_radius,
                     {&fh[i].g, &fh[i].d1, &fh[i].d2});
    });
  }

  const float cmax = float(max_colour_difference()), pccmax = float(kPc) * cmax, qc = float(kQc), pt = float(kPt);
  for_rows(h, [&](int y0, int y1) {
    // Vertical pass of each plane for one row: colour channels, then edges (first derivative)
    // and points (second derivative) in x and y.
    std::vector<std::array<std::vector<float>, 8>> rows(2);
    for (auto& r : rows)
      for (auto& v : r) v.resize(w);
    for (int y = y0; y < y1; ++y) {
      for (int i = 0; i < 2; ++i) {
        auto& r = rows[i];
        filter_column(hz[i].y, w, h, y, f.achromatic, f.csf_radius, r[0].data());
        filter_column(hz[i].cx, w, h, y, f.red_green, f.csf_radius, r[1].data());
        filter_column(hz[i].cz1, w, h, y, f.blue_yellow_1, f.csf_radius, r[2].data());
        filter_column(hz[i].cz2, w, h, y, f.blue_yellow_2, f.csf_radius, r[3].data());
        filter_column(fh[i].d1, w, h, y, f.gauss, f.feature_radius, r[4].data());  // d/dx
        filter_column(fh[i].g, w, h, y, f.d1, f.feature_radius, r[5].data());      // d/dy
        filter_column(fh[i].d2, w, h, y, f.gauss, f.feature_radius, r[6].data());  // d2/dx2
        filter_column(fh[i].g, w, h, y, f.d2, f.feature_radius, r[7].data());      // d2/dy2
      }
      for (int x = 0; x < w; ++x) {
        std::array<float, 3> lab[2];
        float edge[2], point[2];
        for (int i = 0; i < 2; ++i) {
          const auto& r = rows[i];
          lab[i] = filtered_to_lab(r[0][x], r[1][x], r[2][x] + r[3][x]);
          edge[i] = std::sqrt(r[4][x] * r[4][x] + r[5][x] * r[5][x]);
          point[i] = std::sqrt(r[6][x] * r[6][x] + r[7][x] * r[7][x]);
        }
        // Colour: HyAB^qc, the first pc of [0, cmax] spread over [0, pt], the rest over (pt, 1].
        float colour = std::pow(hyab(lab[0], lab[1]), qc);
        colour = colour < pccmax ? colour * (pt / pccmax) : pt + (colour - pccmax) / (cmax - pccmax) * (1.0f - pt);
        // Features: the larger of the edge and the point difference, each at most sqrt(2); the
        // min keeps rounding from making the exponent below negative.
        const float feature_difference =
            std::max(std::abs(edge[0] - edge[1]), std::abs(point[0] - point[1])) * float(1.0 / std::sqrt(2.0));
        const float feature = std::min(std::sqrt(feature_difference), 1.0f);  // ^qf, qf = 0.5
        out[size_t(y) * w + x] = std::pow(colour, 1.0f - feature);
      }
    }
  });
  return out;
}

void check_inputs(const Image& test, const Image& reference, const FlipOptions& options) {
  require_same_shape(test, reference);
  if (test.channels != 3) throw Error("FLIP needs RGB images, not " + std::to_string(test.channels) + " channels");
  if (!(options.ppd > 0.0) || !std::isfinite(options.ppd))
    throw Error("FLIP: pixels per degree must be positive, not " + std::to_string(options.ppd));
}

// The display's view of linear values at exposure 0: non-finite as 0, clamped to [0,1].
Image displayable(const Image& linear) {
  Image out = linear;
  for (float& v : out.data) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  return out;
}

// Row sums in parallel, then over rows in order: the same bits whatever the thread count.
double mean_of(const Plane& map, int w, int h) {
  if (map.empty()) return 0.0;
  std::vector<double> rows(h);
  for_rows(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      double s = 0.0;
      for (int x = 0; x < w; ++x) s += map[size_t(y) * w + x];
      rows[y] = s;
    }
  });
  double sum = 0.0;
  for (double r : rows) sum += r;
  return sum / (double(w) * double(h));
}

FlipResult result_of(Plane map, const Image& shape, bool keep) {
  FlipResult r;
  r.mean = mean_of(map, shape.width, shape.height);
  if (keep) {
    r.map = Image(shape.width, shape.height, 1);
    r.map.data = std::move(map);
  }
  return r;
}

// Narkowicz's ACES fit of 0.6 x: (a x^2 + b x) / (c x^2 + d x + e).
constexpr double kAcesA = 0.6 * 0.6 * 2.51, kAcesB = 0.6 * 0.03, kAcesC = 0.6 * 0.6 * 2.43, kAcesD = 0.6 * 0.59,
                 kAcesE = 0.14;

// The exposure range of the HDR paper: the start exposure maps the reference's largest luminance,
// the stop exposure its median, to where the tone mapper gives 0.85.
void exposure_range(const Image& reference, double& start, double& stop) {
  // x at which ACES(x) = 0.85: the larger root of (a - t c) x^2 + (b - t d) x - t e.
  const double t = 0.85, qa = kAcesA - t * kAcesC, qb = kAcesB - t * kAcesD, qc = -t * kAcesE;
  const double x85 = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
  std::vector<float> lum(reference.pixel_count());
  float lum_max = 0.0f, lum_min_positive = INFINITY;
  for (size_t p = 0; p < lum.size(); ++p) {
    const float* c = &reference.data[p * 3];
    lum[p] = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
    lum_max = std::max(lum_max, lum[p]);
    if (lum[p] > 0.0f) lum_min_positive = std::min(lum_min_positive, lum[p]);
  }
  if (!(lum_max > 0.0f)) {  // a black reference: one exposure serves
    start = stop = 0.0;
    return;
  }
  const size_t mid = lum.size() / 2;
  std::nth_element(lum.begin(), lum.begin() + mid, lum.end());
  // When over half the reference is black, its median says nothing about the visible part: the
  // darkest lit pixel stands in for it.
  const float lum_median = lum[mid] > 0.0f ? lum[mid] : lum_min_positive;
  start = std::log2(x85 / lum_max);
  stop = std::log2(x85 / lum_median);
}

Image expose_and_tone_map(const Image& linear, double exposure) {
  Image out = linear;
  const float scale = float(std::exp2(exposure));
  // Values beyond 1e4 tone-map to 1 as surely as 1e4 does; the bound keeps x^2 finite.
  for (float& v : out.data) v = std::clamp(flip_aces(std::min(v * scale, 1.0e4f)), 0.0f, 1.0f);
  return out;
}

// HDR inputs: non-finite and negative values as 0.
Image non_negative(const Image& linear) {
  Image out = linear;
  for (float& v : out.data) v = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;
  return out;
}

}  // namespace

float flip_aces(float x) {
  const double v = x;
  return float((kAcesA * v * v + kAcesB * v) / (kAcesC * v * v + kAcesD * v + kAcesE));
}

FlipResult flip_ldr(const Image& test, const Image& reference, const FlipOptions& options) {
  check_inputs(test, reference, options);
  const Filters filters = make_filters(options.ppd);
  return result_of(ldr_map(displayable(test), displayable(reference), filters), test, options.keep_map);
}

FlipResult flip_hdr(const Image& test, const Image& reference, const FlipOptions& options) {
  check_inputs(test, reference, options);
  const Image t = non_negative(test), r = non_negative(reference);
  double start = options.start_exposure, stop = options.stop_exposure;
  if (std::isnan(start) || std::isnan(stop)) {
    double auto_start = 0.0, auto_stop = 0.0;
    exposure_range(r, auto_start, auto_stop);
    if (std::isnan(start)) start = auto_start;
    if (std::isnan(stop)) stop = auto_stop;
  }
  if (!std::isfinite(start) || !std::isfinite(stop) || start > stop)
    throw Error("HDR-FLIP: the start exposure (" + std::to_string(start) + ") must be finite and not above the stop (" +
                std::to_string(stop) + ")");
  int count = options.exposures > 0 ? options.exposures : int(std::max(2.0, std::ceil(stop - start)));
  if (count == 1 && start != stop) throw Error("HDR-FLIP: one exposure needs the start exposure equal to the stop");
  const Filters filters = make_filters(options.ppd);
  Plane worst(t.pixel_count(), 0.0f);
  for (int i = 0; i < count; ++i) {
    const double exposure = count == 1 ? start : start + i * (stop - start) / (count - 1);
    const Plane map = ldr_map(expose_and_tone_map(t, exposure), expose_and_tone_map(r, exposure), filters);
    for (size_t p = 0; p < worst.size(); ++p) worst[p] = std::max(worst[p], map[p]);
  }
  FlipResult result = result_of(std::move(worst), test, options.keep_map);
  result.start_exposure = start;
  result.stop_exposure = stop;
  result.exposures = count;
  return result;
}

nlohmann::json flip_json(double ldr, double hdr) {
  return {{"flip_ldr", number_or_null(ldr)}, {"flip_hdr", number_or_null(hdr)}};
}

nlohmann::json flip_metrics(const Image& test, const Image& reference, const FlipOptions& options) {
  if (test.channels != 3 || reference.channels != 3) return flip_json(NAN, NAN);
  return flip_json(flip_ldr(test, reference, options).mean, flip_hdr(test, reference, options).mean);
}

}  // namespace sst
