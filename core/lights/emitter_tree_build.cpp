#include "core/lights/emitter_tree_build.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

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
  // A two-sided node emits about -axis as about +axis, so b's cone may be turned to a's side of
  // the plane: two-sided quads facing opposite ways then merge to a narrow cone, not to the
  // whole sphere (pbrt-v4 unites them as they come).
  vec3 b_axis = b.axis;
  if ((m.flags & EMITTER_TWO_SIDED) != 0u && glm::dot(a.axis, b_axis) < 0.0f) b_axis = -b_axis;
  if (a.axis == b_axis && theta_a == theta_b) return m;  // the common case: one flat emitter
  if (theta_a >= kPiD || theta_b >= kPiD) {              // either holds every direction already
    m.axis = theta_a >= kPiD ? a.axis : b.axis;
    m.cos_o = -1.0f;
    theta = kPiD;
    return m;
  }
  Cone c = cone_union({glm::dvec3(a.axis), theta_a}, {glm::dvec3(b_axis), theta_b});
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

// A light as a leaf of the tree below `parent`.
glsl::EmitterNode leaf_node(const glsl::EmitterNode& light, uint32_t entry, uint32_t parent) {
  glsl::EmitterNode leaf = light;
  leaf.entry = entry;
  leaf.children = 0u;
  leaf.parent = parent;
  return leaf;
}

// The morton build (see the header) of the lights `in_tree` (entries, ascending) into tree.nodes.
void build_morton(std::span<const glsl::EmitterNode> lights, std::vector<uint32_t> in_tree, EmitterTree& tree) {
  const size_t n = in_tree.size();
  Bounds3 centres;
  for (uint32_t i : in_tree) centres.extend(0.5f * (lights[i].lo + lights[i].hi));
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
    const uint32_t node = uint32_t(leaves + k);
    if (k >= n) {  // padding
      tree.nodes[node] = empty_node();
      tree.nodes[node].parent = node / 2;
      theta[node] = 0.0;
      return;
    }
    uint32_t entry = in_tree[k];
    tree.nodes[node] = leaf_node(lights[entry], entry, node / 2);
    theta[node] = theta_of(lights[entry]);
    tree.node_of_entry[entry] = node;
  });
  // Bottom up, one level at a time: a level's nodes are independent.
  for (uint32_t first = leaves / 2; first >= 1; first /= 2) {
    parallel_range(first, size_t(2) * first, [&](size_t i) {
      glsl::EmitterNode m = merge_nodes(tree.nodes[2 * i], theta[2 * i], tree.nodes[2 * i + 1], theta[2 * i + 1], theta[i]);
      m.children = uint32_t(2 * i);
      m.parent = uint32_t(i / 2);
      tree.nodes[i] = m;
    });
  }
}

// A normal cone with its cosine and sine, so that most unions are decided by a dot product.
struct SaohCone {
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double theta = -1.0;  // < 0: empty
  double cos_t = 1.0, sin_t = 0.0;
};

SaohCone saoh_cone(const glm::dvec3& axis, double theta) {
  return {axis, theta, std::cos(theta), std::sin(theta)};
}

// The union of two cones: cone_union, after the cases where one holds the other (cos of the
// angle between the axes at least cos(theta_a - theta_b)), which need no trigonometry.
SaohCone saoh_cone_union(const SaohCone& a, const SaohCone& b) {
  if (b.theta < 0.0) return a;
  if (a.theta < 0.0) return b;
  if (a.theta >= kPiD) return a;
  if (b.theta >= kPiD) return b;
  const double d = glm::dot(a.axis, b.axis);
  const SaohCone& wide = a.theta >= b.theta ? a : b;
  const SaohCone& narrow = a.theta >= b.theta ? b : a;
  if (d >= wide.cos_t * narrow.cos_t + wide.sin_t * narrow.sin_t) return wide;
  Cone c = cone_union({a.axis, a.theta}, {b.axis, b.theta});
  return saoh_cone(c.axis, c.theta);
}

// What the heuristic knows of a set of lights: their box, summed power, normal cone and the
// largest emission spread.
struct SaohBounds {
  Bounds3 box;
  double power = 0.0;
  SaohCone cone;
  double theta_e = 0.0;
  uint32_t count = 0;
  bool two_sided = false;

  void add(const SaohBounds& o) {
    if (o.count == 0) return;
    box.extend(o.box);
    power += o.power;
    two_sided = two_sided || o.two_sided;
    // Turned to this side of the plane when either is two-sided, as merge_nodes does.
    SaohCone c = o.cone;
    if (two_sided && count > 0 && glm::dot(cone.axis, c.axis) < 0.0) c.axis = -c.axis;
    cone = saoh_cone_union(cone, c);
    theta_e = std::max(theta_e, o.theta_e);
    count += o.count;
  }
};

// The surface area of a box whose extents are at least `floor` each: a flat or linear set of
// lights (collinear lamps) still costs by its size, and every split of such a set is not free.
double saoh_area(const Bounds3& box, double floor) {
  const glm::dvec3 e = glm::max(glm::dvec3(box.extent()), glm::dvec3(floor));
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// The heuristic's cost of one side of a split (pbrt-v4's EvaluateCost; Kr and the area floor
// are the node's).
double saoh_cost(const SaohBounds& b, double kr, double floor) {
  if (b.count == 0) return 0.0;
  return b.power * emitter_cone_measure(std::max(0.0, b.cone.theta), b.theta_e) * kr * saoh_area(b.box, floor);
}

struct SaohItem {
  uint32_t entry;
  glm::vec3 centre;
};

constexpr int kSaohBuckets = 12;
// Ranges at least this long are built in parallel with their sibling.
constexpr size_t kSaohParallelRange = 4096;
// Lights binned together; a longer range's chunks are binned in parallel.
constexpr size_t kSaohChunk = 16384;

struct SaohBuilder {
  std::span<const glsl::EmitterNode> lights;
  std::span<const SaohBounds> leaf;  // per entry
  EmitterTree& tree;
  std::vector<double>& theta;        // per node: its merged cone's half angle (merge_nodes)

  // Builds the subtree of `items` at `node`, below `parent`. The node's descendants take the
  // slots from `block` on: its children's pair first, then the left child's descendants
  // (2 m_left - 2 slots), then the right child's. So a subtree of m lights fills 2m - 1 slots,
  // and the layout depends on the splits alone, not on the threads.
  void build(std::span<SaohItem> items, uint32_t node, uint32_t parent, uint32_t block, uint32_t depth) {
    if (items.size() == 1) {
      const uint32_t entry = items[0].entry;
      tree.nodes[node] = leaf_node(lights[entry], entry, parent);
      theta[node] = theta_of(lights[entry]);
      tree.node_of_entry[entry] = node;
      return;
    }
    const size_t mid = split(items, depth);
    const uint32_t left = block, right = block + 1;
    const uint32_t left_block = block + 2, right_block = block + 2 * uint32_t(mid);
    auto build_left = [&] { build(items.subspan(0, mid), left, node, left_block, depth + 1); };
    auto build_right = [&] { build(items.subspan(mid), right, node, right_block, depth + 1); };
    if (items.size() >= kSaohParallelRange) {
      tbb::parallel_invoke(build_left, build_right);
    } else {
      build_left();
      build_right();
    }
    glsl::EmitterNode m = merge_nodes(tree.nodes[left], theta[left], tree.nodes[right], theta[right], theta[node]);
    m.children = left;
    m.parent = parent;
    tree.nodes[node] = m;
  }

  // Reorders items and returns where the left side ends (0 < mid < size).
  size_t split(std::span<SaohItem> items, uint32_t depth) {
    const size_t m = items.size();
    Bounds3 box, centres;
    for (const SaohItem& it : items) {
      box.extend(leaf[it.entry].box);
      centres.extend(it.centre);
    }
    const glm::vec3 extent = box.extent();
    const float widest = std::max(extent.x, std::max(extent.y, extent.z));
    const glm::vec3 spread = centres.extent();
    const int widest_centres = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    // Halves by the centres along their widest axis: where the heuristic has no split (every
    // centre alike) and where the depth left must hold a balanced tree of what remains.
    auto median = [&] {
      const size_t mid = m / 2;
      std::nth_element(items.begin(), items.begin() + mid, items.end(), [&](const SaohItem& a, const SaohItem& b) {
        float ka = a.centre[widest_centres], kb = b.centre[widest_centres];
        return ka != kb ? ka < kb : a.entry < b.entry;
      });
      return mid;
    };
    // Two lights: every split gives the same pair of leaves.
    if (m == 2 || depth + std::bit_width(m - 1) >= kEmitterTreeMaxDepth) return median();
    const double floor = 1e-3 * double(widest);
    double best_cost = std::numeric_limits<double>::infinity();
    int best_dim = -1, best_split = -1;
    const std::array<Buckets, 3> binned = bin(items, centres);
    for (int dim = 0; dim < 3; ++dim) {
      if (!(spread[dim] > 0.0f)) continue;
      const Buckets& buckets = binned[dim];
      // Costs of the splits after bucket i: the left sides in one sweep, the right in another; a
      // side's cost is evaluated again only where an empty bucket did not leave it as it was
      // (short ranges fill few buckets, and most of a build's splits are of short ranges).
      constexpr double kNone = std::numeric_limits<double>::infinity();
      std::array<double, kSaohBuckets - 1> cost{};
      const double kr = double(widest) / double(extent[dim]);
      SaohBounds below;
      double side = kNone;
      for (int i = 0; i < kSaohBuckets - 1; ++i) {
        if (buckets[i].count > 0) {
          below.add(buckets[i]);
          side = saoh_cost(below, kr, floor);
        }
        cost[i] = side;
      }
      SaohBounds above;
      side = kNone;
      for (int i = kSaohBuckets - 1; i >= 1; --i) {
        if (buckets[i].count > 0) {
          above.add(buckets[i]);
          side = saoh_cost(above, kr, floor);
        }
        cost[i - 1] += side;
      }
      for (int i = 0; i < kSaohBuckets - 1; ++i)
        if (cost[i] < best_cost) {
          best_cost = cost[i];
          best_dim = dim;
          best_split = i;
        }
    }
    if (best_dim < 0) return median();
    const float lo = centres.lo[best_dim];
    const float scale = float(kSaohBuckets) / spread[best_dim];
    auto mid = std::stable_partition(items.begin(), items.end(), [&](const SaohItem& it) {
      return bucket_of(it.centre[best_dim], lo, scale) <= best_split;
    });
    const size_t left = size_t(mid - items.begin());
    return left == 0 || left == m ? median() : left;
  }

  static int bucket_of(float x, float lo, float scale) {
    return std::clamp(int((x - lo) * scale), 0, kSaohBuckets - 1);
  }

  using Buckets = std::array<SaohBounds, kSaohBuckets>;

  // The lights in each axis's buckets over the centres' bounds (an axis where they do not spread
  // stays empty). Chunks of kSaohChunk lights are binned in parallel and united in order: the
  // same buckets for any number of threads.
  std::array<Buckets, 3> bin(std::span<const SaohItem> items, const Bounds3& centres) const {
    const glm::vec3 spread = centres.extent();
    auto fill = [&](std::span<const SaohItem> chunk, std::array<Buckets, 3>& out) {
      for (int dim = 0; dim < 3; ++dim) {
        if (!(spread[dim] > 0.0f)) continue;
        const float lo = centres.lo[dim], scale = float(kSaohBuckets) / spread[dim];
        for (const SaohItem& it : chunk) out[dim][bucket_of(it.centre[dim], lo, scale)].add(leaf[it.entry]);
      }
    };
    std::array<Buckets, 3> total;
    const size_t chunks = (items.size() + kSaohChunk - 1) / kSaohChunk;
    if (chunks <= 1) {
      fill(items, total);
      return total;
    }
    std::vector<std::array<Buckets, 3>> partial(chunks);
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
      fill(items.subspan(c * kSaohChunk, std::min(kSaohChunk, items.size() - c * kSaohChunk)), partial[c]);
    });
    for (const std::array<Buckets, 3>& p : partial)
      for (int dim = 0; dim < 3; ++dim)
        for (int b = 0; b < kSaohBuckets; ++b) total[dim][b].add(p[dim][b]);
    return total;
  }
};

// The saoh build (see the header) of the lights `in_tree` into tree.nodes.
void build_saoh(std::span<const glsl::EmitterNode> lights, std::vector<uint32_t> in_tree, EmitterTree& tree) {
  std::vector<SaohBounds> leaf(lights.size());
  std::vector<SaohItem> items(in_tree.size());
  parallel_range(0, in_tree.size(), [&](size_t k) {
    const uint32_t i = in_tree[k];
    const glsl::EmitterNode& l = lights[i];
    SaohBounds& b = leaf[i];
    b.box.lo = l.lo;
    b.box.hi = l.hi;
    const double theta_o = theta_of(l);
    b.theta_e = std::acos(std::clamp(double(l.cos_e), -1.0, 1.0));
    b.cone = saoh_cone(glm::dvec3(l.axis), theta_o);
    // Power, as the heuristic weighs it: the intensity toward the axis over the cone's measure,
    // both sides of a two-sided emitter (a point light 4 pi I, a flat emitter pi Le A).
    b.power = double(l.intensity) * emitter_cone_measure(theta_o, b.theta_e) *
              ((l.flags & EMITTER_TWO_SIDED) ? 2.0 : 1.0);
    b.count = 1;
    b.two_sided = (l.flags & EMITTER_TWO_SIDED) != 0u;
    items[k] = {i, 0.5f * (l.lo + l.hi)};
  });
  std::vector<double> theta(tree.nodes.size(), 0.0);
  SaohBuilder builder{lights, leaf, tree, theta};
  builder.build(items, 1u, 0u, 2u, 0u);
}

}  // namespace

glsl::EmitterNode merge_emitter_nodes(const glsl::EmitterNode& a, const glsl::EmitterNode& b) {
  double theta = 0.0;
  return merge_nodes(a, theta_of(a), b, theta_of(b), theta);
}

const char* emitter_tree_build_names() { return "saoh, morton"; }

const char* emitter_tree_build_name(EmitterTreeBuild build) {
  return build == EmitterTreeBuild::Morton ? "morton" : "saoh";
}

EmitterTreeBuild parse_emitter_tree_build(const std::string& name) {
  if (name == "saoh") return EmitterTreeBuild::Saoh;
  if (name == "morton") return EmitterTreeBuild::Morton;
  throw Error("unknown light tree '" + name + "' (valid: " + emitter_tree_build_names() + ")");
}

const char* emitter_distance_names() { return "centre, box, mixed"; }

const char* emitter_distance_name(EmitterDistance distance) {
  return distance == EmitterDistance::Box ? "box" : distance == EmitterDistance::Mixed ? "mixed" : "centre";
}

EmitterDistance parse_emitter_distance(const std::string& name) {
  for (EmitterDistance d : {EmitterDistance::Centre, EmitterDistance::Box, EmitterDistance::Mixed})
    if (name == emitter_distance_name(d)) return d;
  throw Error("unknown light tree distance '" + name + "' (valid: " + emitter_distance_names() + ")");
}

double emitter_cone_measure(double theta_o, double theta_e) {
  const double theta_w = std::min(theta_o + theta_e, kPiD);
  const double cos_o = std::cos(theta_o), sin_o = std::sin(theta_o);
  return 2.0 * kPiD * (1.0 - cos_o) +
         0.5 * kPiD * (2.0 * theta_w * sin_o - std::cos(theta_o - 2.0 * theta_w) - 2.0 * theta_o * sin_o + cos_o);
}

EmitterTree build_emitter_tree(std::span<const glsl::EmitterNode> lights, EmitterTreeBuild build) {
  EmitterTree tree;
  tree.node_of_entry.assign(lights.size(), LIGHT_NONE);
  std::vector<uint32_t> in_tree;
  std::vector<uint32_t> directional;
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const glsl::EmitterNode& l = lights[i];
    if (!usable(l)) continue;
    (l.flags & EMITTER_DIRECTIONAL ? directional : in_tree).push_back(i);
  }
  const size_t n = in_tree.size();
  if (n > (size_t(1) << 30)) throw Error("emitter tree: too many lights (" + std::to_string(n) + ")");
  tree.leaves = n == 0 ? 0u : build == EmitterTreeBuild::Morton ? std::bit_ceil(uint32_t(n)) : uint32_t(n);
  tree.directional_count = uint32_t(directional.size());
  const size_t node_count = size_t(2) * tree.leaves + directional.size();
  resize_uninitialized(tree.nodes, node_count, /*huge_pages=*/true);  // unwritten: every node is written once below
  if (tree.leaves > 0) tree.nodes[0] = empty_node();
  if (build == EmitterTreeBuild::Morton)
    build_morton(lights, std::move(in_tree), tree);
  else if (n > 0)
    build_saoh(lights, std::move(in_tree), tree);
  for (uint32_t k = 0; k < directional.size(); ++k) {
    uint32_t node = 2 * tree.leaves + k;
    tree.nodes[node] = lights[directional[k]];
    tree.nodes[node].entry = directional[k];
    tree.nodes[node].children = 0u;
    tree.nodes[node].parent = 0u;
    tree.node_of_entry[directional[k]] = node;
  }
  return tree;
}

void emitter_tree_cut(std::span<const glsl::EmitterNode> nodes, uint32_t leaves, uint32_t directional_count,
                      uint32_t distance, bool seen, glm::vec3 p, glm::vec3 n, uint32_t max_nodes,
                      std::vector<uint32_t>& cut) {
  struct Candidate {
    uint32_t node;
    float importance, intensity;
    bool operator<(const Candidate& o) const {
      return importance != o.importance ? importance < o.importance : intensity < o.intensity;
    }
  };
  auto make = [&](uint32_t i) {
    const glsl::EmitterNode& e = nodes[i];
    float w = seen && e.children != 0u ? emitter_importance(e, p, n, distance) : 0.0f;
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
      if (nodes[list[i].node].children != 0u && (best < 0 || list[best] < list[i])) best = int(i);
    if (best < 0) break;  // only leaves left
    uint32_t node = list[best].node;
    list.erase(list.begin() + best);
    const uint32_t first = nodes[node].children;
    for (uint32_t c : {first, first + 1})
      if (nodes[c].intensity > 0.0f) list.push_back(make(c));
  }
  for (const Candidate& c : list) cut.push_back(c.node);
}

}  // namespace sst
