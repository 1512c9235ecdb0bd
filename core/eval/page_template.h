// Pages rendered from a JSON view model with the Mustache templates of core/eval/report/. The
// templates (and the style sheet and script they pull in) are embedded in the binary at build
// time, so a program that writes a page needs no files beside it.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace sst {

// Renders the embedded template `name` (e.g. "report.html") with `view`. Every embedded file is a
// partial by its file name ({{> table.html}}, {{> report.css}}). In the view, strings are text,
// numbers are written as JSON writes them, and null, false and empty lists are false in sections;
// {{...}} escapes as html_escape does. Throws std::runtime_error for an unknown or malformed
// template (a build defect: the tests render every template).
std::string render_page_template(std::string_view name, const nlohmann::json& view);

// &, <, >, " and ' as entities, other control characters than tab and newline as spaces: safe in
// HTML and in inline SVG (XML 1.0 forbids those characters) as text and as attribute values.
std::string html_escape(std::string_view text);

}  // namespace sst
