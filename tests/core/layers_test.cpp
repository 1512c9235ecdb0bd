// The folders of app/, core/ and gpu/ form the stack of layers written in core/LAYERS.txt: every
// #include (C++ and GLSL) points to the including file's own folder or to a lower layer, and the
// folder-level include graph has no cycle.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = SST_SOURCE_DIR;

struct Include {
  std::string file;  // relative to the source root
  int line = 0;
  std::string target;  // as written
  std::string from, to;  // folders
};

// The folder of a path relative to the source root: "app", "gpu" (with its subfolders), or the
// core folder that holds the file, "core/<concept>" or a folder nested in one
// ("core/manylight/<method>").
std::string folder_of(const std::string& path) {
  fs::path p(path);
  if (p.empty()) return "";
  std::string top = p.begin()->string();
  return top == "core" ? p.parent_path().generic_string() : top;
}

// The layer index of each folder, 0 = top. A pattern `<folder>/*` stands for every folder directly
// inside <folder> that the file does not name itself.
struct Layers {
  std::map<std::string, int> named;
  std::map<std::string, int> patterns;  // <folder> of `<folder>/*`
  bool empty() const { return named.empty() && patterns.empty(); }
  // The layer of `folder`; -1 when it is not listed.
  int of(const std::string& folder) const {
    if (auto it = named.find(folder); it != named.end()) return it->second;
    if (auto it = patterns.find(fs::path(folder).parent_path().generic_string()); it != patterns.end())
      return it->second;
    return -1;
  }
};

// core/LAYERS.txt; *error describes a malformed file.
Layers read_layers(std::string* error) {
  std::ifstream in(kRoot / "core" / "LAYERS.txt");
  if (!in) {
    *error = "cannot read core/LAYERS.txt";
    return {};
  }
  Layers layers;
  std::string line;
  int index = 0;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string folder;
    bool any = false;
    while (words >> folder) {
      bool pattern = folder.size() > 2 && folder.compare(folder.size() - 2, 2, "/*") == 0;
      std::map<std::string, int>& to = pattern ? layers.patterns : layers.named;
      std::string key = pattern ? folder.substr(0, folder.size() - 2) : folder;
      if (to.count(key)) *error += "core/LAYERS.txt lists " + folder + " twice\n";
      to[key] = index;
      any = true;
    }
    if (any) ++index;
  }
  return layers;
}

// Every quoted #include in app/, core/ and gpu/, resolved as the compilers do: first beside the
// including file, then from the source root (-I for both compilers).
std::vector<Include> scan_includes(std::vector<std::string>* unresolved) {
  static const std::regex include_re(R"(^\s*#\s*include\s*"([^"]+)\")");
  static const std::set<std::string> extensions = {".h", ".cpp", ".glsl", ".comp"};
  std::vector<Include> includes;
  for (const char* top : {"app", "core", "gpu"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
      if (!entry.is_regular_file() || !extensions.count(entry.path().extension().string())) continue;
      std::string file = fs::relative(entry.path(), kRoot).generic_string();
      std::ifstream in(entry.path());
      std::string text;
      int line_number = 0;
      while (std::getline(in, text)) {
        ++line_number;
        std::smatch m;
        if (!std::regex_search(text, m, include_re)) continue;
        std::string target = m[1];
        fs::path beside = entry.path().parent_path() / target;
        fs::path resolved;
        if (fs::exists(beside)) resolved = beside;
        else if (fs::exists(kRoot / target)) resolved = kRoot / target;
        else {
          unresolved->push_back(file + ":" + std::to_string(line_number) + ": \"" + target + "\" not found");
          continue;
        }
        std::string to = fs::relative(fs::weakly_canonical(resolved), fs::weakly_canonical(kRoot)).generic_string();
        includes.push_back({file, line_number, target, folder_of(file), folder_of(to)});
      }
    }
  }
  return includes;
}

TEST(Layers, EveryIncludePointsDown) {
  std::string error;
  Layers layers = read_layers(&error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_FALSE(layers.empty());
  std::vector<std::string> unresolved;
  std::vector<Include> includes = scan_includes(&unresolved);
  EXPECT_GT(includes.size(), 100u);  // the scan found the sources
  for (const std::string& u : unresolved) ADD_FAILURE() << u;
  std::set<std::string> unlisted;
  for (const Include& inc : includes) {
    for (const std::string& f : {inc.from, inc.to})
      if (layers.of(f) < 0 && unlisted.insert(f).second)
        ADD_FAILURE() << "folder " << f << " (" << (f == inc.from ? inc.file : inc.target)
                      << ") is not listed in core/LAYERS.txt";
    int from = layers.of(inc.from), to = layers.of(inc.to);
    if (inc.from == inc.to || from < 0 || to < 0) continue;
    if (to <= from)
      ADD_FAILURE() << inc.file << ":" << inc.line << ": #include \"" << inc.target << "\": " << inc.from
                    << " (layer " << from << ") includes " << inc.to << " (layer " << to << "), "
                    << (to == from ? "a folder of the same layer" : "a higher layer")
                    << "; see core/LAYERS.txt";
  }
}

TEST(Layers, FolderIncludeGraphHasNoCycle) {
  std::vector<std::string> unresolved;
  std::map<std::string, std::map<std::string, std::string>> edges;  // from -> to -> an example file:line
  for (const Include& inc : scan_includes(&unresolved))
    if (inc.from != inc.to) edges[inc.from].emplace(inc.to, inc.file + ":" + std::to_string(inc.line));
  // Depth-first search; a back edge closes a cycle, reported with one include per arrow.
  std::map<std::string, int> state;  // 0 new, 1 on the stack, 2 done
  std::vector<std::string> stack;
  std::string cycle;
  std::function<void(const std::string&)> visit = [&](const std::string& f) {
    state[f] = 1;
    stack.push_back(f);
    for (const auto& [to, where] : edges[f]) {
      if (!cycle.empty()) break;
      if (state[to] == 1) {
        auto it = std::find(stack.begin(), stack.end(), to);
        for (; it != stack.end(); ++it) {
          const std::string& next = (it + 1 == stack.end()) ? to : *(it + 1);
          cycle += *it + " -> " + next + " (" + edges[*it][next] + ")\n";
        }
      } else if (state[to] == 0) {
        visit(to);
      }
    }
    stack.pop_back();
    state[f] = 2;
  };
  std::vector<std::string> folders;
  for (const auto& [from, to] : edges) folders.push_back(from);
  for (const std::string& f : folders)
    if (cycle.empty() && state[f] == 0) visit(f);
  EXPECT_TRUE(cycle.empty()) << "the folders include each other in a cycle:\n" << cycle;
}

}  // namespace
