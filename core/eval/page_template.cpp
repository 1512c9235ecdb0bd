#include "core/eval/page_template.h"

#include <kainjow/mustache.hpp>

#include <stdexcept>
#include <vector>

namespace sst {

// Defined by the build (cmake/embed.cmake) from the files of core/eval/report/.
std::string_view report_asset(std::string_view name);
std::vector<std::string_view> report_asset_names();

namespace {

namespace mustache = kainjow::mustache;

mustache::data to_data(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      mustache::data out{mustache::data::type::object};
      for (auto it = j.begin(); it != j.end(); ++it) out.set(it.key(), to_data(it.value()));
      return out;
    }
    case nlohmann::json::value_t::array: {
      mustache::data out{mustache::data::type::list};
      for (const nlohmann::json& item : j) out.push_back(to_data(item));
      return out;
    }
    case nlohmann::json::value_t::string:
      return mustache::data{j.get<std::string>()};
    case nlohmann::json::value_t::boolean:
      return mustache::data{j.get<bool>()};
    // Present but false, so that a section on it is skipped instead of Mustache looking the key
    // up in the enclosing objects.
    case nlohmann::json::value_t::null:
    case nlohmann::json::value_t::discarded:
      return mustache::data{false};
    default:
      return mustache::data{j.dump()};
  }
}

// A file's text without its final newline, so that a partial used inside a line (a table cell,
// a span of text) does not break it.
std::string partial_text(std::string_view name) {
  std::string text(report_asset(name));
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

}  // namespace

std::string html_escape(std::string_view text) {
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
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') ? ' ' : c;
    }
  }
  return out;
}

std::string render_page_template(std::string_view name, const nlohmann::json& view) {
  const std::string_view source = report_asset(name);
  if (source.empty()) throw std::runtime_error("no embedded template named '" + std::string(name) + "'");
  mustache::data data = to_data(view.is_object() ? view : nlohmann::json::object());
  for (std::string_view asset : report_asset_names()) {
    const std::string text = partial_text(asset);
    data.set(std::string(asset), mustache::partial([text] { return text; }));
  }
  mustache::mustache page{std::string(source)};
  page.set_custom_escape([](const std::string& s) { return html_escape(s); });
  std::string out = page.render(data);
  if (!page.is_valid()) throw std::runtime_error("template " + std::string(name) + ": " + page.error_message());
  return out;
}

}  // namespace sst
