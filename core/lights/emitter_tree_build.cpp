#include "core/lights/emitter_tree_build.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/lights/light_sampler.h"
#include "core/math/math.h"
#include "core/math/morton.h"
#include "core/math/radix_sort.h"
#include "core/util/error.h"
#include "core/util/memory.h"

namespace sst {
namespace {

constexpr double kPiD = 3.14159265358979323846;

struct Cone {
  glm::dvec3 axis;
  double theta;  // half angle, [0, pi]
};

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// pbrt-v4's DirectionCone::Union: the smallest cone (about a direction between the two axes)
// that holds both.
Cone cone_union(const Cone& a, const Cone& b) {
  double d = angle_between(a.axis, b.axis);
  if (std::min(d + b.theta, kPiD) <= a.theta) return a;
  if (std::min(d + a.theta, kPiD) <= b.theta) return b;
  double theta = 0.5 * (a.theta + d + b.theta);
  if (theta >= kPiD) return {a.axis, kPiD};
  glm::dvec3 r = glm::cross(a.axis, b.axis);
  double r2 = glm::dot(r, r);
  if (!(r2 > 0.0)) return {a.axis, kPiD};  // opposite axes
  // a's axis turned toward b's by theta - theta_a, in the plane of the two.
  double turn = theta - a.theta;
  glm::dvec3 side = glm::normalize(glm::cross(r / std::sqrt(r2), a.axis));
  glm::dvec3 axis = glm::normalize(a.axis * std::cos(turn) + side * std::sin(turn));
  return {axis, theta};
}

// The largest float not above cos(angle): a stored cone never narrower than the angle. (Near pi
// one float step of the cosine is several times kConeSlack of angle, so rounding to nearest
// could undo the slack.)
float cos_at_most(double angle) {
  double c = std::cos(angle);
  float f = float(c);
  return double(f) > c ? std::nextafter(f, -2.0f) : f;
}

glsl::EmitterNode empty_node() {
  glsl::EmitterNode n{};
  n.lo = vec3(0.0f);
  n.hi = vec3(0.0f);
  n.intensity = 0.0f;
  n.axis = vec3(0.0f, 0.0f, 1.0f);
  n.cos_o = 1.0f;
  n.cos_e = 1.0f;
  n.flags = 0u;
  n.entry = LIGHT_NONE;
  return n;
}

template <class F>
void parallel_range(size_t begin, size_t end, const F& f) {
  tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 2048), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

bool usable(const glsl::EmitterNode& n) { return n.intensity > 0.0f && std::isfinite(n.intensity); }

// Merges a and b whose normal cones have half angles theta_a and theta_b (the doubles the build
// keeps beside the nodes, so no level reads a cone back through its float cosine, whose steps
// near pi are wider than the slack); the merged half angle, slack included, goes to `theta`.
glsl::EmitterNode merge_nodes(const glsl::EmitterNode& a, double theta_a, const glsl::EmitterNode& b, double theta_b,
                              double& theta) {
  theta = 0.0;
  if (!usable(a) && !usable(b)) return empty_node();
  glsl::EmitterNode m = usable(a) ? a : b;
  theta = usable(a) ? theta_a : theta_b;
  m.entry = LIGHT_NONE;
  if (!usable(a) || !usable(b)) return m;
  m.lo = glm::min(a.lo, b.lo);
  m.hi = glm::max(a.hi, b.hi);
  m.intensity = a.intensity + b.intensity;
  m.flags = (a.flags | b.flags) & EMITTER_TWO_SIDED;
  m.cos_e = std::min(a.cos_e, b.cos_e);
  if (a.axis == b.axis && theta_a == theta_b) return m;  // the common case: one flat emitter
  if (theta_a >= kPiD || theta_b >= kPiD) {              // either holds every direction already
    m.axis = theta_a >= kPiD ? a.axis : b.axis;
    m.cos_o = -1.0f;
    theta = kPiD;
    return m;
  }
  Cone c = cone_union({glm::dvec3(a.axis), theta_a}, {glm::dvec3(b.axis), theta_b});
  m.axis = vec3(c.axis);
  theta = std::min(kPiD, c.theta + kConeSlack);
  m.cos_o = theta >= kPiD ? -1.0f : cos_at_most(theta);
  return m;
}

// The half angle of n's normal cone; a flat emitter's (cos_o 1) and a point light's (-1) without acos.
double theta_of(const glsl::EmitterNode& n) {
  if (n.cos_o >= 1.0f) return 0.0;
  if (n.cos_o <= -1.0f) return kPiD;
  return std::acos(double(n.cos_o));
}

}  // namespace

glsl::EmitterNode merge_emitter_nodes(const glsl::EmitterNode& a, const glsl::EmitterNode& b) {
  double theta = 0.0;
  return merge_nodes(a, theta_of(a), b, theta_of(b), theta);
}

EmitterTree build_emitter_tree(std::span<const glsl::EmitterNode> lights) {
  EmitterTree tree;
  tree.node_of_entry.assign(lights.size(), LIGHT_NONE);
  std::vector<uint32_t> in_tree;
  std::vector<uint32_t> directional;
  Bounds3 centres;
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const glsl::EmitterNode& l = lights[i];
    if (!usable(l)) continue;
    if (l.flags & EMITTER_DIRECTIONAL) {
      directional.push_back(i);
      continue;
    }
    in_tree.push_back(i);
    centres.extend(0.5f * (l.lo + l.hi));
  }
  const size_t n = in_tree.size();
  if (n > (size_t(1) << 30)) throw Error("emitter tree: too many lights (" + std::to_string(n) + ")");
  tree.leaves = n == 0 ? 0u : std::bit_ceil(uint32_t(n));
  tree.directional_count = uint32_t(directional.size());
  const size_t node_count = size_t(2) * tree.leaves + directional.size();
  resize_uninitialized(tree.nodes, node_count, /*huge_pages=*/true);  // unwritten: every node is written once below
  if (tree.leaves > 0) tree.nodes[0] = empty_node();

  // Morton order of the centres, ties by entry: a stable radix sort of the codes alone, since the
  // entries come in ascending order.
  const MortonGrid grid = MortonGrid::over(centres);
  std::vector<uint64_t> keys(n);
  parallel_range(0, n, [&](size_t i) {
    const glsl::EmitterNode& l = lights[in_tree[i]];
    keys[i] = grid.code(0.5f * (l.lo + l.hi));
  });
  radix_sort_pairs(keys, in_tree, 0, kMortonBits);

  const uint32_t leaves = tree.leaves;
  UninitializedVector<double> theta;  // written for every node with the node
  resize_uninitialized(theta, size_t(2) * leaves, /*huge_pages=*/true);
  parallel_range(0, leaves, [&](size_t k) {
    if (k >= n) {  // padding
      tree.nodes[leaves + k] = empty_node();
      theta[leaves + k] = 0.0;
      return;
    }
    uint32_t entry = in_tree[k];
    glsl::EmitterNode leaf = lights[entry];
    leaf.entry = entry;
    tree.nodes[leaves + k] = leaf;
    theta[leaves + k] = theta_of(leaf);
    tree.node_of_entry[entry] = uint32_t(leaves + k);
  });
  // Bottom up, one level at a time: a level's nodes are independent.
  for (uint32_t first = leaves / 2; first >= 1; first /= 2) {
    parallel_range(first, size_t(2) * first, [&](size_t i) {
      tree.nodes[i] = merge_nodes(tree.nodes[2 * i], theta[2 * i], tree.nodes[2 * i + 1], theta[2 * i + 1], theta[i]);
    });
  }
  for (uint32_t k = 0; k < directional.size(); ++k) {
    uint32_t node = 2 * leaves + k;
    tree.nodes[node] = lights[directional[k]];
    tree.nodes[node].entry = directional[k];
    tree.node_of_entry[directional[k]] = node;
  }
  return tree;
}

void emitter_tree_cut(std::span<const glsl::EmitterNode> nodes, uint32_t leaves, uint32_t directional_count,
                      bool seen, glm::vec3 p, glm::vec3 n, uint32_t max_nodes, std::vector<uint32_t>& cut) {
  struct Candidate {
    uint32_t node;
    float importance, intensity;
    bool operator<(const Candidate& o) const {
      return importance != o.importance ? importance < o.importance : intensity < o.intensity;
    }
  };
  auto make = [&](uint32_t i) {
    const glsl::EmitterNode& e = nodes[i];
    float w = seen && i < leaves ? emitter_importance(e, p, n) : 0.0f;
    return Candidate{i, std::isfinite(w) ? w : (std::isinf(w) ? 3.0e38f : 0.0f), e.intensity};
  };
  // Cuts are at most a few dozen nodes: a linear scan beats a heap.
  std::vector<Candidate> list;
  if (leaves > 0 && nodes[1].intensity > 0.0f) list.push_back(make(1));
  for (uint32_t k = 0; k < directional_count; ++k)
    if (nodes[2 * leaves + k].intensity > 0.0f) list.push_back(make(2 * leaves + k));
  while (list.size() < max_nodes) {
    int best = -1;
    for (size_t i = 0; i < list.size(); ++i)
      if (list[i].node < leaves && (best < 0 || list[best] < list[i])) best = int(i);
    if (best < 0) break;  // only leaves left
    uint32_t node = list[best].node;
    list.erase(list.begin() + best);
    for (uint32_t c : {2 * node, 2 * node + 1})
      if (nodes[c].intensity > 0.0f) list.push_back(make(c));
  }
  for (const Candidate& c : list) cut.push_back(c.node);
}

}  // namespace sst
