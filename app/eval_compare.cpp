#include "app/eval_compare.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/image/image.h"
#include "core/metrics/error_map.h"
#include "core/metrics/flip.h"
#include "core/metrics/metrics.h"
#include "core/metrics/same_shape.h"
#include "core/util/error.h"

namespace sst::app {
namespace {

struct Input {
  Image values;  // as stored: display values for PNG/JPEG, linear otherwise
  bool display = false;
};

Input load(const std::string& path, const std::string& layer) {
  if (!layer.empty()) return {read_layer(path, layer), false};
  Input in;
  in.values = read_image_stored(path, &in.display);
  return in;
}

Image linear_of(const Input& in) { return in.display ? from_display(in.values) : in.values; }

// Two PNGs are compared on their stored 8-bit levels; any other pair on linear values.
ImageMetrics metrics_of(const Input& test, const Input& reference) {
  if (test.display && reference.display) return compare_images(test.values, reference.values, true);
  return compare_images(linear_of(test), linear_of(reference), false);
}

// LDR- and HDR-FLIP (core/metrics/flip.h) of linear RGB images, NaN otherwise. HDR-FLIP needs HDR:
// a pair of display images (PNGs) has LDR-FLIP only, as the FLIP tool reports them.
struct Flip {
  FlipResult ldr, hdr;
};

Flip flip_of(const CompareArgs& args, const Image& test, const Image& reference, bool display_pair) {
  Flip f;
  f.ldr.mean = f.hdr.mean = NAN;
  if (test.channels != 3) return f;
  FlipOptions options;
  options.keep_map = !args.flip_map.empty();
  f.ldr = flip_ldr(test, reference, options);
  if (!display_pair) {
    options.keep_map = !args.flip_hdr_map.empty();
    f.hdr = flip_hdr(test, reference, options);
  }
  return f;
}

// An EXR holds the map's values (grey); any other format the inferno colour map of them.
void write_flip_map(const std::string& path, const FlipResult& r, const char* which) {
  if (r.map.data.empty()) throw Error(std::string("no ") + which + " map for " + path + ": it needs RGB" +
                                      (std::string(which) == "HDR-FLIP" ? " HDR inputs" : " inputs"));
  const bool exr = path.size() >= 4 && path.compare(path.size() - 4, 4, ".exr") == 0;
  if (!exr) return write_image(path, inferno_image(r.map));
  Image grey(r.map.width, r.map.height, 3);
  for (size_t p = 0; p < r.map.pixel_count(); ++p)
    for (int c = 0; c < 3; ++c) grey.data[p * 3 + c] = r.map.data[p];
  write_image(path, grey);
}

void print_table(const CompareArgs& args, const ImageMetrics& m, const MaskedErrors* masked, const Flip& flip) {
  std::printf("test       %s%s\n", args.test.c_str(),
              args.layer.empty() ? "" : (" [" + args.layer + "]").c_str());
  std::printf("reference  %s%s\n", args.reference.c_str(),
              args.layer.empty() ? "" : (" [" + args.layer + "]").c_str());
  std::printf("size       %dx%d\n", m.width, m.height);
  std::printf("rmse       %.6g\n", m.rmse);
  std::printf("rel_mse    %.6g\n", m.rel_mse);
  std::printf("psnr       %.4g dB\n", m.psnr);
  std::printf("ssim       %.6f\n", m.ssim);
  std::printf("mae        %.6g\n", m.mae);
  if (std::isfinite(flip.ldr.mean))
    std::printf("flip_ldr   %.6f\n", flip.ldr.mean);
  else
    std::printf("flip_ldr   -  (FLIP needs RGB inputs)\n");
  if (std::isfinite(flip.hdr.mean))
    std::printf("flip_hdr   %.6f (%d exposures, %.3g to %.3g)\n", flip.hdr.mean, flip.hdr.exposures,
                flip.hdr.start_exposure, flip.hdr.stop_exposure);
  else
    std::printf("flip_hdr   -  (HDR-FLIP needs linear RGB inputs)\n");
  std::printf("mean_test  %10.6g %10.6g %10.6g\n", m.mean_test.x, m.mean_test.y, m.mean_test.z);
  std::printf("mean_ref   %10.6g %10.6g %10.6g\n", m.mean_reference.x, m.mean_reference.y,
              m.mean_reference.z);
  if (m.nonfinite_test || m.nonfinite_reference)
    std::printf("nonfinite  %zu test, %zu reference pixels (counted as 0)\n", m.nonfinite_test,
                m.nonfinite_reference);
  if (masked)
    std::printf("masked     %zu pixels where the mask is 0: rmse %.6g, rel_mse %.6g, mae %.6g\n", masked->pixels,
                masked->rmse, masked->rel_mse, masked->mae);
}

void print_json(const CompareArgs& args, const ImageMetrics& m, const MaskedErrors* masked, const Flip& flip) {
  nlohmann::json out = to_json(m);
  out.update(flip_json(flip.ldr.mean, flip.hdr.mean));
  if (masked)
    out["masked"] = {{"mask", args.mask}, {"pixels", masked->pixels}, {"rmse", masked->rmse},
                     {"rel_mse", masked->rel_mse}, {"mae", masked->mae}};
  out["test"] = args.test;
  out["reference"] = args.reference;
  out["layer"] = args.layer.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.layer);
  out["heatmap"] = args.heatmap.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.heatmap);
  std::printf("%s\n", out.dump(2).c_str());
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareArgs& args) {
  CLI::App* cmd = app.add_subcommand("compare", "Metrics of a test image against a reference");
  cmd->add_option("test", args.test, "Test image (.exr, .hdr, .png)")->required();
  cmd->add_option("reference", args.reference, "Reference image")->required();
  cmd->add_flag("--json", args.json, "Print one JSON object instead of a table");
  cmd->add_option("--heatmap", args.heatmap,
                  "Write the per-pixel relative error as a heat map (e.g. err.png)");
  cmd->add_option("--heatmap-max", args.heatmap_max, "Relative error shown as the brightest colour")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--layer", args.layer, "Compare this EXR layer (e.g. indirect) of both files");
  cmd->add_option("--mask", args.mask,
                  "Also report rmse, rel_mse and mae over the pixels where this image is 0 (e.g. a render of "
                  "the emitters alone: the pixels no visible emitter touches)");
  cmd->add_option("--flip-map", args.flip_map,
                  "Write the LDR-FLIP error map (.exr: its values, in every channel; other formats: the inferno colour "
                  "map, 0 black .. 1 pale yellow)");
  cmd->add_option("--flip-hdr-map", args.flip_hdr_map, "Write the HDR-FLIP error map, as --flip-map");
  return cmd;
}

int run_compare(const CompareArgs& args) {
  const Input test = load(args.test, args.layer);
  const Input reference = load(args.reference, args.layer);
  if (test.values.width != reference.values.width || test.values.height != reference.values.height ||
      test.values.channels != reference.values.channels)
    throw Error("cannot compare " + args.test + " (" + shape_string(test.values) + ") with " +
                args.reference + " (" + shape_string(reference.values) + "): sizes differ");
  const ImageMetrics m = metrics_of(test, reference);
  const Image linear_test = linear_of(test), linear_reference = linear_of(reference);
  MaskedErrors masked;
  if (!args.mask.empty()) masked = masked_errors(linear_test, linear_reference, linear_of(load(args.mask, "")));
  const MaskedErrors* masked_or_null = args.mask.empty() ? nullptr : &masked;
  if (!args.heatmap.empty()) write_image(args.heatmap, error_heatmap(linear_test, linear_reference, args.heatmap_max));
  const Flip flip = flip_of(args, linear_test, linear_reference, test.display && reference.display);
  if (!args.flip_map.empty()) write_flip_map(args.flip_map, flip.ldr, "LDR-FLIP");
  if (!args.flip_hdr_map.empty()) write_flip_map(args.flip_hdr_map, flip.hdr, "HDR-FLIP");
  if (args.json)
    print_json(args, m, masked_or_null, flip);
  else
    print_table(args, m, masked_or_null, flip);
  return 0;
}

}  // namespace sst::app
