#include "core/eval/report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
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

// ---- reading the view model

const json& section(const json& view, const std::string& name) {
  for (const json& s : view["sections"])
    if (s["name"] == name) return s;
  ADD_FAILURE() << "no section " << name;
  static const json none;
  return none;
}

// The values of the section's blocks of one kind ("table", "plots", "images", ...), in order.
std::vector<json> blocks(const json& section, const std::string& kind) {
  std::vector<json> out;
  for (const json& b : section["blocks"])
    if (b.contains(kind)) out.push_back(b[kind]);
  return out;
}

std::vector<json> all_blocks(const json& view, const std::string& kind) {
  std::vector<json> out;
  for (const json& s : view["sections"])
    for (json& b : blocks(s, kind)) out.push_back(std::move(b));
  return out;
}

std::vector<json> figures(const json& view) {
  std::vector<json> out;
  for (const json& grid : all_blocks(view, "images"))
    for (const json& card : grid["cards"])
      for (const json& f : card["figures"]) out.push_back(f);
  return out;
}

std::string plain(const json& spans) {
  std::string s;
  for (const json& span : spans) s += span["text"].get<std::string>();
  return s;
}

// The cell texts of a table's column, by its head's text.
std::vector<std::string> column(const json& table, const std::string& head) {
  size_t at = 0;
  while (at < table["head"]["cells"].size() && table["head"]["cells"][at]["text"] != head) ++at;
  EXPECT_LT(at, table["head"]["cells"].size()) << head;
  std::vector<std::string> out;
  for (const json& row : table["rows"]) out.push_back(row["cells"].at(at)["text"]);
  return out;
}

// The group table row whose label and axes text match.
const json& group_row(const json& table, const std::string& label, const std::string& vpls) {
  const std::vector<std::string> labels = column(table, "label"), vpl = column(table, "vpls");
  for (size_t i = 0; i < labels.size(); ++i)
    if (labels[i] == label && vpl[i] == vpls) return table["rows"][i];
  ADD_FAILURE() << "no row " << label << " " << vpls;
  static const json none;
  return none;
}

std::vector<json> plots(const json& view) {
  std::vector<json> out;
  for (const json& b : all_blocks(view, "plots"))
    for (const json& p : b["items"]) out.push_back(p);
  return out;
}

size_t marker_count(const json& plot) {
  size_t n = 0;
  for (const json& s : plot["series"]) n += s["markers"].size();
  return n;
}

TEST(Report, ContainsEveryRunIdAndImagePath) {
  const json r = fixture();
  const json view = report_view(r);
  ASSERT_EQ(r["runs"].size(), 20u);
  const std::vector<std::string> ids = column(view["runs"]["table"], "id");
  std::vector<std::string> srcs;
  for (const json& f : figures(view)) srcs.push_back(f["src"]);
  auto shown = [&](const std::string& src) { return std::count(srcs.begin(), srcs.end(), src); };
  for (const json& run : r["runs"]) {
    EXPECT_EQ(std::count(ids.begin(), ids.end(), run["id"].get<std::string>()), 1) << run["id"];
    // The comparison view shows each group's seed-0 run.
    EXPECT_EQ(shown(run["images"]["png"]), run["seed"] == 0 ? 1 : 0) << run["id"];
    EXPECT_EQ(shown(run["images"]["error_png"]), run["seed"] == 0 ? 1 : 0) << run["id"];
  }
  for (const auto& [id, ref] : r["references"].items()) EXPECT_EQ(shown(ref["image_png"]), 1) << id;
}

TEST(Report, ComparisonShowsTheSeedZeroRunOfEachGroupBesideItsReference) {
  const json r = fixture();
  const json view = report_view(r);
  size_t flips = 0, errors = 0, stair_refs = 0;
  for (const json& f : figures(view)) {
    if (f["flip"].is_object()) {
      ++flips;
      EXPECT_EQ(f["flip"]["run"], f["src"]);
      EXPECT_TRUE(f["src"].get<std::string>().starts_with("runs/" + f["flip"]["id"].get<std::string>() + "/"));
      stair_refs += f["flip"]["ref"] == std::string("references/") + kStairRef + ".png";
    }
    if (f["ramp"] == true) {
      ++errors;
      EXPECT_EQ(f["caption"], "relative error, 0 (black) .. \u22651 (yellow)");
    }
    EXPECT_EQ(f["aspect"], "160 / 120");
  }
  EXPECT_EQ(flips, r["groups"].size());
  EXPECT_EQ(errors, r["groups"].size());
  EXPECT_EQ(stair_refs, r["groups"].size() / 2);
  for (const json& run : r["runs"])
    if (run["seed"] == 0) {
      bool found = false;
      for (const json& f : figures(view)) found |= f["flip"].is_object() && f["flip"]["id"] == run["id"];
      EXPECT_TRUE(found) << run["id"];
    }
  const json card = all_blocks(view, "images").at(0)["cards"].at(1);  // after the reference's card
  EXPECT_EQ(plain(card["heading"]), "pt");
  EXPECT_EQ(plain(card["sub"]), "run 0000-pt (seed 0), RMSE 0.09000, SSIM 0.8000, 40.00 ms");
}

TEST(Report, HeaderSaysWhatTheMetricsAreAgainst) {
  const json view = report_view(fixture());
  EXPECT_EQ(view["title"], "sst-eval report: demo");
  std::map<std::string, std::string> facts;
  for (const json& row : view["facts"]["rows"]) facts[row["cells"][0]["text"]] = row["cells"][1]["text"];
  EXPECT_EQ(facts["tool revision"], "abc1234");
  EXPECT_EQ(facts["machine"], "Test CPU 9000; 2 threads; os: Linux");
  EXPECT_EQ(facts["device"], "cpu: Test CPU 9000");
  EXPECT_EQ(facts["runs"], "20 runs in 10 groups over 2 scene(s)");
  const json& refs = view["references"];
  EXPECT_EQ(column(refs, "what"), (std::vector<std::string>{"path tracer, 1024 spp, 8 bounces, 160\u00d7120",
                                                            "VPL ground truth (exhaustive), 16 spp, 100000 VPLs, 160\u00d7120"}));
  EXPECT_EQ(column(refs, "render time")[0], "81.23 s");
  EXPECT_EQ(column(refs, "reference"), (std::vector<std::string>{kCornellRef, kStairRef}));
  EXPECT_EQ(plain(blocks(section(view, "staircase.gltf"), "paragraph").at(0)["spans"]),
            std::string("metrics against reference ") + kStairRef + ": VPL ground truth (exhaustive), 16 spp, 100000 VPLs, 160\u00d7120");
}

TEST(Report, HasATablePerSceneAndAllRunsInDetails) {
  const json r = fixture();
  const json view = report_view(r);
  ASSERT_EQ(view["sections"].size(), 2u);
  EXPECT_EQ(view["sections"][0]["name"], "cornell-box.gltf");
  EXPECT_EQ(view["sections"][1]["name"], "staircase.gltf");
  for (const json& s : view["sections"]) {
    const std::vector<json> tables = blocks(s, "table");
    ASSERT_EQ(tables.size(), 1u);
    EXPECT_EQ(tables[0]["class"], "groups");
    EXPECT_EQ(tables[0]["rows"].size(), 5u);
  }
  EXPECT_EQ(view["runs"]["summary"], "All 20 runs");
  EXPECT_EQ(view["runs"]["table"]["rows"].size(), 20u);
}

TEST(Report, FormatsNumbersWithFourSignificantDigits) {
  json r = fixture();
  r["runs"][0]["time_ms"]["median"] = 12.34567;
  r["runs"][0]["metrics"]["rmse"] = 0.0123456;
  r["runs"][0]["metrics"]["ssim"] = nullptr;
  const json runs = report_view(r)["runs"]["table"];
  EXPECT_EQ(column(runs, "time ms")[0], "12.35");
  EXPECT_EQ(column(runs, "RMSE")[0], "0.01235");
  EXPECT_EQ(column(runs, "SSIM")[0], "\u2014");  // a null is a dash
  EXPECT_EQ(column(runs, "SSIM")[1], "0.8000");
  EXPECT_EQ(runs["rows"][0]["cells"][0]["code"], true);  // the id
}

TEST(Report, TimeCellShowsTheMedianAndTheRangeOverRuns) {
  // Group slc vpls=1000 of the first scene: median 4 ms, runs 4 and 4.04 ms, min 0.97x, max 1.05x.
  const json table = blocks(report_view(fixture())["sections"][0], "table").at(0);
  const json& time = group_row(table, "slc", "1000")["cells"].at(4);
  EXPECT_EQ(time["text"], "4.000");
  EXPECT_EQ(time["note"], "[3.880..4.242]");
}

TEST(Report, MarksParetoRows) {
  const json r = fixture();
  const json view = report_view(r);
  size_t pareto = 0, marked = 0;
  for (const json& g : r["groups"]) pareto += g["pareto"] == true;
  ASSERT_GT(pareto, 0u);
  ASSERT_LT(pareto, r["groups"].size());
  for (const json& table : all_blocks(view, "table"))
    for (const json& row : table["rows"]) {
      const bool on_front = row["class"] == "pareto";
      marked += on_front;
      EXPECT_EQ(row["cells"][0]["text"], on_front ? "\u2605" : "");
      EXPECT_EQ(row["cells"][0]["class"], "mark");
    }
  EXPECT_EQ(marked, pareto);
  // The fastest group of each scene (sst vpls=1000) is always on the front.
  for (const json& table : all_blocks(view, "table")) EXPECT_EQ(group_row(table, "sst", "1000")["class"], "pareto");
}

TEST(Report, DrawsThreePlotsPerSceneWhenVplsVary) {
  const json view = report_view(fixture());
  const std::vector<json> all = plots(view);
  ASSERT_EQ(all.size(), 6u);
  std::vector<std::string> titles;
  for (const json& p : all) titles.push_back(p["title"]);
  EXPECT_EQ(titles, (std::vector<std::string>{"RMSE vs time: cornell-box.gltf", "RMSE vs VPL count: cornell-box.gltf",
                                              "Time vs VPL count: cornell-box.gltf", "RMSE vs time: staircase.gltf",
                                              "RMSE vs VPL count: staircase.gltf", "Time vs VPL count: staircase.gltf"}));
  EXPECT_EQ(all[0]["highlight"]["name"], "Pareto front");  // the dashed line, RMSE vs time only
  EXPECT_TRUE(all[1]["highlight"].is_null());
  EXPECT_EQ(all[0]["x_axis"]["scale"], "log10");
  EXPECT_EQ(all[2]["y_axis"]["scale"], "linear");
  // 5 groups per scene: 5 markers in the RMSE-vs-time plot, less pt's in the two VPL plots.
  for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(marker_count(all[i]), i % 3 == 0 ? 5u : 4u) << i;
}

TEST(Report, KeepsOneColourPerLabelAcrossPlots) {
  // Labels in order of appearance: pt, slc, sst -> palette entries 0, 1, 2 in every plot, though
  // slc is the first series of the VPL plots (pt has no VPLs).
  for (const json& p : plots(report_view(fixture()))) {
    for (const json& s : p["series"]) {
      const std::string name = s["name"];
      const char* colour = name == "pt" ? "#4e79a7" : name.starts_with("slc") ? "#f28e2b" : "#e15759";
      EXPECT_EQ(s["colour"], colour) << name;
    }
  }
}

TEST(Report, SppColumnShowsTheRenderedCount) {
  json r = fixture();
  for (json& g : r["groups"])
    if (g["label"] == "pt") g["axes"] = {{"spp", 4}};  // an spp axis gets no column of its own
  const json table = blocks(report_view(r)["sections"][0], "table").at(0);
  std::vector<std::string> heads;
  for (const json& c : table["head"]["cells"]) heads.push_back(c["text"]);
  EXPECT_EQ(std::count(heads.begin(), heads.end(), "spp"), 1);
  const json& pt = group_row(table, "pt", "\u2014");
  EXPECT_EQ(pt["cells"][3]["text"], "4");
}

TEST(Report, OmitsPlotsWithFewerThanTwoPoints) {
  json r = fixture();
  // Keep one group per scene: no plot has two points.
  json groups = json::array();
  for (const json& g : r["groups"])
    if (g["label"] == "pt") groups.push_back(g);
  r["groups"] = groups;
  json view = report_view(r);
  EXPECT_EQ(all_blocks(view, "plots").size(), 0u);
  EXPECT_EQ(all_blocks(view, "table").size(), 2u);

  // VPL counts that do not vary: only the RMSE-vs-time plot.
  r = fixture();
  for (json& g : r["groups"])
    if (g["axes"].contains("vpls") && g["axes"]["vpls"] == 1000) g["axes"]["vpls"] = 10000;
  view = report_view(r);
  ASSERT_EQ(plots(view).size(), 2u);
  for (const json& p : plots(view)) EXPECT_TRUE(p["title"].get<std::string>().starts_with("RMSE vs time"));
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
  const json view = report_view(r);
  std::vector<std::string> srcs;
  for (const json& f : figures(view)) srcs.push_back(f["src"]);
  EXPECT_EQ(std::count(srcs.begin(), srcs.end(), "runs/a%20b%23c/image.png"), 1);
  EXPECT_EQ(std::count(srcs.begin(), srcs.end(), "javascript%3Aalert%281%29"), 1);
  EXPECT_FALSE(contains(make_report_html(r), "javascript:"));
}

TEST(Report, ToleratesMissingFields) {
  EXPECT_NO_THROW(make_report_html(json::object()));
  EXPECT_NO_THROW(make_report_html(json(nullptr)));
  json r = fixture(1);  // one seed: std, bias² and variance are null
  r["runs"][3].erase("metrics");
  r["runs"][4].erase("time_ms");
  r["groups"][1]["runs"].push_back("no-such-run");
  r.erase("references");
  const json view = report_view(r);
  for (const json& table : all_blocks(view, "table"))
    for (const std::string& rmse : column(table, "RMSE")) EXPECT_FALSE(contains(rmse, "\u00b1")) << rmse;
  EXPECT_TRUE(contains(render_report(view), "</html>"));
}

TEST(Report, IsDeterministic) {
  const json r = fixture();
  const std::string html = make_report_html(r);
  EXPECT_EQ(html, make_report_html(r));
  EXPECT_EQ(html, make_report_html(json::parse(r.dump())));
}

// Mustache looks a key missing from an object up in the enclosing ones (a row without a class
// would take its table's), so every cell and figure spells out every key its template reads.
TEST(Report, CellsAndFiguresHaveEveryKey) {
  const json view = report_view(fixture());
  std::vector<json> tables = all_blocks(view, "table");
  tables.insert(tables.end(), {view["facts"], view["references"], view["runs"]["table"]});
  const std::set<std::string> cell_keys{"text", "note", "code", "class", "title", "header"};
  for (const json& table : tables) {
    for (const char* key : {"class", "head", "rows", "note"}) EXPECT_TRUE(table.contains(key)) << key;
    std::vector<json> cells = table["head"].is_null() ? std::vector<json>{} : table["head"]["cells"].get<std::vector<json>>();
    for (const json& row : table["rows"]) {
      EXPECT_TRUE(row.contains("class"));
      for (const json& c : row["cells"]) cells.push_back(c);
    }
    for (const json& c : cells) {
      std::set<std::string> keys;
      for (const auto& [k, v] : c.items()) keys.insert(k);
      EXPECT_EQ(keys, cell_keys) << c.dump();
    }
  }
  const std::set<std::string> figure_keys{"src", "video", "link", "alt", "caption", "ramp", "flip", "aspect"};
  for (const json& f : figures(view)) {
    std::set<std::string> keys;
    for (const auto& [k, v] : f.items()) keys.insert(k);
    EXPECT_EQ(keys, figure_keys) << f.dump();
  }
}

// ---- the rendered page: a smoke test of the templates, not of their markup

TEST(Report, RenderedPageIsWellFormed) {
  const json r = fixture();
  const json view = report_view(r);
  const std::string html = render_report(view);
  EXPECT_TRUE(html.starts_with("<!DOCTYPE html>"));
  EXPECT_TRUE(contains(html, "<title>sst-eval report: demo</title>"));
  EXPECT_FALSE(contains(html, "{{"));
  EXPECT_FALSE(contains(html, "}}"));
  EXPECT_EQ(count(html, "<svg"), plots(view).size());
  EXPECT_EQ(count(html, "</svg>"), plots(view).size());
  for (const char* tag : {"table", "section", "figure", "details", "g", "text", "div", "tr"})
    EXPECT_EQ(count(html, std::string("<") + tag + ">") + count(html, std::string("<") + tag + " "),
              count(html, std::string("</") + tag + ">"))
        << tag;
  size_t pareto = 0;
  for (const json& g : r["groups"]) pareto += g["pareto"] == true;
  EXPECT_EQ(count(html, "<tr class=\"pareto\">"), pareto);  // the view's row classes reach the page
  EXPECT_EQ(count(html, "<tr class="), pareto);              // and no row takes its table's class
  EXPECT_EQ(count(html, "<img class=\"flip\""), 10u);
}

TEST(Report, PageEmbedsStyleAndScriptVerbatim) {
  const std::string html = make_report_html(fixture());
  for (const char* line : {".pane img, .pane video { display: block; width: 100%; image-rendering: pixelated; }",
                           "document.querySelectorAll('.compare').forEach(function (box) {"})
    EXPECT_TRUE(contains(html, line)) << line;
  EXPECT_EQ(count(html, "<style>"), 1u);
  EXPECT_EQ(count(html, "<script>"), 1u);
}

TEST(Report, VideoFiguresPlayLoopingBesideStills) {
  json view = report_view(fixture());
  json& grid = view["sections"][0]["blocks"].back()["images"];
  grid["cards"][0]["figures"].push_back(video_figure("runs/0000-pt/preview.mp4", "animated", "160 / 120"));
  const std::string html = render_report(view);
  EXPECT_TRUE(contains(html, "<video src=\"runs/0000-pt/preview.mp4\" autoplay loop muted playsinline></video>"));
  EXPECT_EQ(count(html, "<video"), 1u);
  EXPECT_TRUE(contains(html, "<figcaption>animated</figcaption>"));
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
