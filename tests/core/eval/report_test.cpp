#include "core/eval/report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sst {
namespace {

using nlohmann::json;

size_t count(const std::string& haystack, const std::string& needle) {
  size_t n = 0;
  for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + 1)) ++n;
  return n;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

struct Point {
  std::string label, method;
  json axes;
  double time_ms, rmse;
};

// A sweep point's runs over `seeds` seeds, with times and errors that vary a little by seed.
void add_group(json& results, const std::string& scene, const std::string& ref, const Point& p, int seeds) {
  json group = {{"group", p.label + " " + p.axes.dump()},
                {"label", p.label},
                {"scene", scene},
                {"method", p.method},
                {"axes", p.axes},
                {"runs", json::array()},
                {"seeds", seeds}};
  for (int seed = 0; seed < seeds; ++seed) {
    const int index = int(results["runs"].size());
    char id[64];
    std::snprintf(id, sizeof(id), "%04d-%s", index, p.method.c_str());
    const double t = p.time_ms * (1 + 0.01 * seed), e = p.rmse * (1 + 0.05 * seed);
    json params = {{"method", p.method}, {"spp", 4}, {"width", 160}, {"height", 120}, {"seed", seed}};
    if (p.axes.contains("vpls")) params["vpls"] = p.axes["vpls"];
    const std::string dir = std::string("runs/") + id;
    results["runs"].push_back(
        {{"id", id},
         {"index", index},
         {"group", group["group"]},
         {"label", p.label},
         {"scene", scene},
         {"method", p.method},
         {"variant", ""},
         {"axes", p.axes},
         {"seed", seed},
         {"params", params},
         {"reference", ref},
         {"time_budget_ms", nullptr},
         {"spp", 4},
         {"time_ms", {{"median", t}, {"min", t * 0.97}, {"max", t * 1.05}}},
         {"metrics", {{"rmse", e}, {"rel_mse", e * 2}, {"psnr", 30 + seed}, {"ssim", 0.8}}},
         {"efficiency", 1 / (e * e * t / 1000)},
         {"ssim_gain_pct_per_ms", nullptr},
         {"gain_base", "0000-pt"},
         {"images", {{"exr", dir + "/image.exr"}, {"png", dir + "/image.png"}, {"error_png", dir + "/error.png"}}}});
    group["runs"].push_back(id);
  }
  group["time_ms_median"] = p.time_ms;
  group["rmse_mean"] = p.rmse;
  group["rmse_std"] = seeds > 1 ? json(p.rmse * 0.03) : json(nullptr);
  group["ssim_mean"] = 0.8;
  group["bias2"] = seeds > 1 ? json(p.rmse * p.rmse * 0.5) : json(nullptr);
  group["variance"] = seeds > 1 ? json(p.rmse * p.rmse * 0.5) : json(nullptr);
  results["groups"].push_back(group);
}

// Marks each scene's groups that no faster group beats in RMSE.
void mark_pareto(json& results) {
  for (json& g : results["groups"]) {
    bool dominated = false;
    for (const json& o : results["groups"])
      dominated |=
          o["scene"] == g["scene"] && o["time_ms_median"] < g["time_ms_median"] && o["rmse_mean"] <= g["rmse_mean"];
    g["pareto"] = !dominated;
  }
}

const char* const kCornellRef = "a1b2c3d4e5f60718";
const char* const kStairRef = "0f1e2d3c4b5a6978";

// Two scenes, three labels (pt, slc, sst), slc/sst over two VPL counts, two seeds per point.
json fixture(int seeds = 2) {
  json r = {{"schema_version", 1},
            {"tool", "sst-eval"},
            {"tool_revision", "abc1234"},
            {"machine", {{"cpu", "Test CPU 9000"}, {"hardware_threads", 2}, {"os", "Linux"}}},
            {"device", "cpu: Test CPU 9000"},
            {"name", "demo"},
            {"config", json::object()},
            {"runs", json::array()},
            {"groups", json::array()}};
  r["references"][kCornellRef] = {
      {"kind", "path"},
      {"scene", "cornell-box.gltf"},
      {"image_png", std::string("references/") + kCornellRef + ".png"},
      {"params", {{"method", "pt"}, {"spp", 1024}, {"max_bounces", 8}, {"width", 160}, {"height", 120}}},
      {"render_ms", 81234.5}};
  r["references"][kStairRef] = {
      {"kind", "vpl"},
      {"scene", "staircase.gltf"},
      {"image_png", std::string("references/") + kStairRef + ".png"},
      {"params", {{"method", "exhaustive"}, {"spp", 16}, {"vpls", 100000}, {"width", 160}, {"height", 120}}},
      {"render_ms", 5000}};
  for (const auto& [scene, ref] : {std::pair{"cornell-box.gltf", kCornellRef}, {"staircase.gltf", kStairRef}}) {
    add_group(r, scene, ref, {"pt", "pt", json::object(), 40.0, 0.09}, seeds);
    for (int vpls : {1000, 10000}) {
      add_group(r, scene, ref, {"slc", "slc", {{"vpls", vpls}}, vpls * 0.004, 0.2 / std::sqrt(vpls)}, seeds);
      add_group(r, scene, ref, {"sst", "sst", {{"vpls", vpls}}, vpls * 0.002, 0.3 / std::sqrt(vpls)}, seeds);
    }
  }
  mark_pareto(r);
  return r;
}

TEST(Report, ContainsEveryRunIdAndImagePath) {
  const json r = fixture();
  const std::string html = make_report_html(r);
  ASSERT_EQ(r["runs"].size(), 20u);
  for (const json& run : r["runs"]) {
    EXPECT_TRUE(contains(html, run["id"].get<std::string>())) << run["id"];
    if (run["seed"] == 0) {  // the comparison view shows each group's seed-0 run
      EXPECT_TRUE(contains(html, "src=\"" + run["images"]["png"].get<std::string>() + "\"")) << run["id"];
      EXPECT_TRUE(contains(html, "src=\"" + run["images"]["error_png"].get<std::string>() + "\"")) << run["id"];
    }
  }
  for (const auto& [id, ref] : r["references"].items())
    EXPECT_TRUE(contains(html, "src=\"" + ref["image_png"].get<std::string>() + "\"")) << id;
}

TEST(Report, ComparisonShowsTheSeedZeroRunOfEachGroupBesideItsReference) {
  const json r = fixture();
  const std::string html = make_report_html(r);
  EXPECT_EQ(count(html, "<img class=\"flip\""), r["groups"].size());
  for (const json& run : r["runs"]) {
    const std::string png = run["images"]["png"];
    EXPECT_EQ(count(html, "data-run=\"" + png + "\""), run["seed"] == 0 ? 1u : 0u) << png;
  }
  EXPECT_EQ(count(html, std::string("data-ref=\"references/") + kStairRef + ".png\""), r["groups"].size() / 2);
  EXPECT_EQ(count(html, "relative error, 0 (black) .. \u22651 (yellow)"), r["groups"].size());
  EXPECT_TRUE(contains(html, "image-rendering: pixelated"));
  EXPECT_TRUE(contains(html, "<select class=\"zoom\">"));
}

TEST(Report, HeaderSaysWhatTheMetricsAreAgainst) {
  const std::string html = make_report_html(fixture());
  EXPECT_TRUE(contains(html, "<h1>sst-eval report: demo</h1>"));
  EXPECT_TRUE(contains(html, "abc1234"));
  EXPECT_TRUE(contains(html, "Test CPU 9000; 2 threads"));
  EXPECT_TRUE(contains(html, "cpu: Test CPU 9000"));
  EXPECT_TRUE(contains(html, "20 runs in 10 groups over 2 scene(s)"));
  EXPECT_TRUE(contains(html, "path tracer, 1024 spp, 8 bounces, 160\u00d7120"));
  EXPECT_TRUE(contains(html, "VPL ground truth (exhaustive), 16 spp, 100000 VPLs"));
  EXPECT_TRUE(contains(html, "81.23 s"));  // reference render time
}

TEST(Report, HasATablePerSceneAndAllRunsInDetails) {
  const json r = fixture();
  const std::string html = make_report_html(r);
  EXPECT_EQ(count(html, "<table class=\"groups\">"), 2u);
  EXPECT_EQ(count(html, "<section class=\"scene\"><h2>cornell-box.gltf</h2>"), 1u);
  EXPECT_EQ(count(html, "<section class=\"scene\"><h2>staircase.gltf</h2>"), 1u);
  const size_t details = html.find("<details class=\"runs\"><summary>All 20 runs</summary>");
  ASSERT_NE(details, std::string::npos);
  for (const json& run : r["runs"])
    EXPECT_NE(html.find("<code>" + run["id"].get<std::string>() + "</code>", details), std::string::npos);
}

TEST(Report, FormatsNumbersWithFourSignificantDigits) {
  json r = fixture();
  r["runs"][0]["time_ms"]["median"] = 12.34567;
  r["runs"][0]["metrics"]["rmse"] = 0.0123456;
  r["runs"][0]["metrics"]["ssim"] = nullptr;
  const std::string html = make_report_html(r);
  EXPECT_TRUE(contains(html, ">12.35<"));
  EXPECT_TRUE(contains(html, ">0.01235<"));
  EXPECT_TRUE(contains(html, "<td class=\"num\">\u2014</td>"));  // a null is a dash
  EXPECT_FALSE(contains(html, "12.34567"));
  EXPECT_FALSE(contains(html, "nan"));
}

TEST(Report, TimeCellShowsTheMedianAndTheRangeOverRuns) {
  const json r = fixture();
  // Group slc vpls=1000 of the first scene: median 4 ms, runs 4 and 4.04 ms, min 0.97x, max 1.05x.
  EXPECT_TRUE(contains(make_report_html(r), "4.000 <span class=\"range\">[3.880..4.242]</span>"));
}

TEST(Report, MarksParetoRows) {
  const json r = fixture();
  const std::string html = make_report_html(r);
  size_t pareto = 0;
  for (const json& g : r["groups"]) pareto += g["pareto"] == true;
  ASSERT_GT(pareto, 0u);
  ASSERT_LT(pareto, r["groups"].size());
  EXPECT_EQ(count(html, "<tr class=\"pareto\">"), pareto);
  // The fastest group of each scene (sst vpls=1000) is always on the front.
  EXPECT_TRUE(contains(html,
                       "<tr class=\"pareto\"><td class=\"mark\" title=\"on the RMSE-vs-time Pareto front\">"
                       "\u2605</td><td class=\"label\">sst</td><td class=\"num\">1000</td>"));
}

TEST(Report, DrawsThreePlotsPerSceneWhenVplsVary) {
  const std::string html = make_report_html(fixture());
  EXPECT_EQ(count(html, "<svg"), 6u);
  EXPECT_EQ(count(html, "RMSE vs time: cornell-box.gltf"), 1u);
  EXPECT_EQ(count(html, "RMSE vs VPL count: staircase.gltf"), 1u);
  EXPECT_EQ(count(html, "Time vs VPL count: staircase.gltf"), 1u);
  EXPECT_EQ(count(html, "stroke-dasharray=\"6 4\""), 2u * 2u);  // the Pareto line and its legend, per scene
  // 5 groups per scene: 5 markers in each of the 3 plots, less pt's in the two VPL plots.
  EXPECT_EQ(count(html, "class=\"marker\""), 2u * (5u + 4u + 4u));
}

TEST(Report, KeepsOneColourPerLabelAcrossPlots) {
  const std::string html = make_report_html(fixture());
  // Labels in order of appearance: pt, slc, sst -> palette entries 0, 1, 2 in every plot, though
  // slc is the first series of the VPL plots (pt has no VPLs).
  const std::string slc_marker = "class=\"marker\" fill=\"#f28e2b\"";
  EXPECT_EQ(count(html, slc_marker), 2u * (2u + 2u + 2u));
  EXPECT_EQ(count(html, "class=\"marker\" fill=\"#4e79a7\""), 2u * 1u);  // pt, only in RMSE vs time
}

TEST(Report, SppColumnShowsTheRenderedCount) {
  json r = fixture();
  for (json& g : r["groups"])
    if (g["label"] == "pt") g["axes"] = {{"spp", 4}};  // an spp axis gets no column of its own
  const std::string html = make_report_html(r);
  EXPECT_EQ(count(html, "<th>spp</th>"), 2u + 1u);  // a group table per scene, and the runs table
  EXPECT_TRUE(contains(html, "<td class=\"label\">pt</td><td class=\"num\">\u2014</td><td class=\"num\">4</td>"));
}

TEST(Report, OmitsPlotsWithFewerThanTwoPoints) {
  json r = fixture();
  // Keep one group per scene: no plot has two points.
  json groups = json::array();
  for (const json& g : r["groups"])
    if (g["label"] == "pt") groups.push_back(g);
  r["groups"] = groups;
  std::string html = make_report_html(r);
  EXPECT_EQ(count(html, "<svg"), 0u);
  EXPECT_EQ(count(html, "<table class=\"groups\">"), 2u);

  // VPL counts that do not vary: only the RMSE-vs-time plot.
  r = fixture();
  for (json& g : r["groups"])
    if (g["axes"].contains("vpls") && g["axes"]["vpls"] == 1000) g["axes"]["vpls"] = 10000;
  html = make_report_html(r);
  EXPECT_EQ(count(html, "<svg"), 2u);
  EXPECT_EQ(count(html, "VPL count"), 0u);
}

TEST(Report, EscapesStringsFromTheResults) {
  json r = fixture();
  r["groups"][0]["label"] = "<script>alert(1)</script>";
  r["runs"][0]["label"] = "<script>alert(1)</script>";
  r["name"] = "a&b";
  r["device"] = "\"quoted\"";
  const std::string html = make_report_html(r);
  EXPECT_EQ(count(html, "<script"), 1u);  // the report's own script only
  EXPECT_FALSE(contains(html, "alert(1)</script>"));
  EXPECT_TRUE(contains(html, "&lt;script&gt;alert(1)&lt;/script&gt;"));
  EXPECT_TRUE(contains(html, "sst-eval report: a&amp;b"));
  EXPECT_TRUE(contains(html, "&quot;quoted&quot;"));
}

TEST(Report, EncodesImagePathsAsRelativeUrls) {
  json r = fixture();
  r["runs"][0]["images"]["png"] = "runs/a b#c/image.png";
  r["runs"][0]["images"]["error_png"] = "javascript:alert(1)";
  const std::string html = make_report_html(r);
  EXPECT_TRUE(contains(html, "src=\"runs/a%20b%23c/image.png\""));
  EXPECT_TRUE(contains(html, "src=\"javascript%3Aalert%281%29\""));
  EXPECT_FALSE(contains(html, "javascript:"));
}

TEST(Report, ToleratesMissingFields) {
  EXPECT_NO_THROW(make_report_html(json::object()));
  EXPECT_NO_THROW(make_report_html(json(nullptr)));
  json r = fixture(1);  // one seed: std, bias² and variance are null
  r["runs"][3].erase("metrics");
  r["runs"][4].erase("time_ms");
  r["groups"][1]["runs"].push_back("no-such-run");
  r.erase("references");
  const std::string html = make_report_html(r);
  EXPECT_TRUE(contains(html, "</html>"));
  EXPECT_FALSE(contains(html, " \u00b1 0"));  // no "mean ± std" cell
}

TEST(Report, IsDeterministic) {
  const json r = fixture();
  const std::string html = make_report_html(r);
  EXPECT_EQ(html, make_report_html(r));
  EXPECT_EQ(html, make_report_html(json::parse(r.dump())));
}

TEST(Report, WriteReportWritesReportHtmlInTheResultsFolder) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sst-report-test-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const json r = fixture();
  write_report(r, (dir / "results").string());
  std::ifstream in(dir / "results" / "report.html");
  std::stringstream text;
  text << in.rdbuf();
  // The fixture's images do not exist in this folder: the written page leaves them out.
  EXPECT_NE(text.str(), make_report_html(r));
  EXPECT_EQ(text.str().find("error.png"), std::string::npos);
  EXPECT_NE(text.str().find("0000-pt"), std::string::npos);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "results"), fs::directory_iterator()), 1);  // no temp file left
  fs::remove_all(dir);
}

TEST(Report, WriteReportKeepsImagesThatExist) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sst-report-test-kept-" + std::to_string(getpid()));
  fs::remove_all(dir);
  json r = fixture();
  for (const json& run : r["runs"])
    for (const auto& [kind, path] : run["images"].items()) {
      fs::create_directories((dir / path.get<std::string>()).parent_path());
      std::ofstream(dir / path.get<std::string>()) << "png";
    }
  for (const auto& [id, ref] : r["references"].items()) {
    fs::create_directories((dir / ref["image_png"].get<std::string>()).parent_path());
    std::ofstream(dir / ref["image_png"].get<std::string>()) << "png";
  }
  write_report(r, dir.string());
  std::ifstream in(dir / "report.html");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), make_report_html(r));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sst
