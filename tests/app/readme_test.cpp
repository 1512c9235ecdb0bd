// docs/methods.md's section on methods and parameters is generated (sst-render --list-methods
// --markdown, from the registry's descriptions and the visit() help strings); this fails when
// the page no longer holds exactly what the program prints, and says how to regenerate it.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/test_util.h"

namespace sst {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first line that differs between a and b, 1-based, with both versions of it.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    bool ga = bool(std::getline(sa, la)), gb = bool(std::getline(sb, lb));
    if (!ga && !gb) return "";
    if (!ga) la = "(end of section)";
    if (!gb) lb = "(end of section)";
    if (la != lb || !ga || !gb)
      return "line " + std::to_string(line) + " of the section:\n  docs:      " + la + "\n  generated: " + lb;
  }
}

TEST(Readme, MethodSectionIsGenerated) {
  auto r = test::run_command(std::string(SST_RENDER_EXE) + " --list-methods --markdown 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string& generated = r.output;
  // The generated text starts with the begin marker line and ends with the end marker line.
  std::string begin = generated.substr(0, generated.find('\n') + 1);
  std::string end = generated.substr(generated.rfind('\n', generated.size() - 2) + 1);
  ASSERT_EQ(begin.rfind("<!-- methods:", 0), 0u) << generated;
  ASSERT_EQ(end, "<!-- end methods -->\n") << generated;

  std::string doc_path = std::string(SST_SOURCE_DIR) + "/docs/methods.md";
  std::string doc = read_text(doc_path);
  std::string regenerate = "regenerate it with: scripts/update_readme_methods.sh build/sst-render";
  size_t from = doc.find("\n" + begin);
  size_t to = from == std::string::npos ? from : doc.find("\n" + end, from);
  ASSERT_NE(to, std::string::npos) << doc_path << " has no section from '" << begin.substr(0, begin.size() - 1)
                                   << "' to '" << end.substr(0, end.size() - 1) << "'; add the two lines, then "
                                   << regenerate;
  std::string section = doc.substr(from + 1, to + end.size() - from);
  EXPECT_TRUE(section == generated) << doc_path << ": the methods section differs from `sst-render --list-methods "
                                    << "--markdown`, at " << first_difference(section, generated) << "\n"
                                    << regenerate;
}

}  // namespace
}  // namespace sst
