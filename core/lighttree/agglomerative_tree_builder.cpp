// The light-tree builders' slow, high-quality baseline (docs/design/methods.md): greedy
// agglomerative clustering as in Lightcuts (Walter et al. 2005, §4.1): repeatedly merge the pair
// of clusters whose union is smallest by the oriented-light size metric
//     M(C) = I_C (alpha_C^2 + c^2 (1 - cos beta_C)^2),
// I_C the cluster's luminance, alpha_C its box diagonal, beta_C the half-angle of the cone
// bounding its normals and c = D, the tree's length scale (Walter: the scene diagonal).
//
// Every cluster caches its best partner; a heap holds the candidate pairs. Merging A and B can
// only make M(L, A u B) >= M(L, A), so only clusters whose best partner was A or B search again
// (O(active clusters) each). Time is O(n^2) for the first search plus the re-searches, so
// n is limited to kMaxAgglomerativeVpls (20000 random VPLs: ~3 s on 2 cores; 5000: ~0.25 s). Ties are broken by (id distance, id), which keeps the
// order deterministic and spreads the partners of all-equal clusters (coincident or black VPLs)
// instead of making them all wait for the same one.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <queue>
#include <string>

#include "core/lighttree/tree_builders.h"
#include "core/util/error.h"

namespace sst {
namespace {

struct Cluster {
  vec3 lo, hi;
  float weight;  // luminance, floored (see weight_floor below)
  vec3 axis;     // normal cone
  float theta;   // its half-angle in [0, pi]
};

float angle_between(vec3 a, vec3 b) { return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)); }

// Half-angle of the cone bounding cones a and b (the union of pbrt-v4's DirectionCone).
float union_angle(const Cluster& a, const Cluster& b) {
  float d = angle_between(a.axis, b.axis);
  if (std::min(d + b.theta, kPi) <= a.theta) return a.theta;
  if (std::min(d + a.theta, kPi) <= b.theta) return b.theta;
  return std::min(0.5f * (a.theta + d + b.theta), kPi);
}

vec3 union_axis(const Cluster& a, const Cluster& b, float theta) {
  float d = angle_between(a.axis, b.axis);
  if (std::min(d + b.theta, kPi) <= a.theta) return a.axis;
  if (std::min(d + a.theta, kPi) <= b.theta) return b.axis;
  if (theta >= kPi) return a.axis;
  // Rotate a's axis towards b's by theta - a.theta, in their common plane.
  vec3 ortho = b.axis - glm::dot(a.axis, b.axis) * a.axis;
  float length = glm::length(ortho);
  vec3 dir = length > 1e-6f ? ortho / length : basis_from_normal(a.axis).t;  // opposite axes
  float r = theta - a.theta;
  return glm::normalize(std::cos(r) * a.axis + std::sin(r) * dir);
}

struct Metric {
  float c2;  // c^2 = D^2
  // M(a u b), or any value >= `bound` once M is known to be at least that: the box term alone
  // is a lower bound and needs no trigonometry, which skips most candidates of a search.
  float operator()(const Cluster& a, const Cluster& b, float bound = kInf) const {
    vec3 extent = glm::max(a.hi, b.hi) - glm::min(a.lo, b.lo);
    float weight = a.weight + b.weight;
    float size = weight * glm::dot(extent, extent);
    if (size > bound) return size;
    float orientation = 1.0f - std::cos(union_angle(a, b));
    return size + weight * c2 * orientation * orientation;
  }
};

struct Candidate {
  float metric = kInf;
  uint32_t distance = UINT32_MAX;
  uint32_t partner = UINT32_MAX;
  bool operator<(const Candidate& o) const {
    if (metric != o.metric) return metric < o.metric;
    if (distance != o.distance) return distance < o.distance;
    return partner < o.partner;
  }
};

struct HeapEntry {
  Candidate candidate;
  uint32_t self;
  bool operator>(const HeapEntry& o) const {
    if (candidate.metric != o.candidate.metric) return candidate.metric > o.candidate.metric;
    if (self != o.self) return self > o.self;
    return o.candidate < candidate;
  }
};

class Clustering {
 public:
  Clustering(const VplSet& vpls, float length_scale, float weight_floor) : metric_{sqr(length_scale)} {
    size_t n = vpls.size();
    clusters_.resize(2 * n - 1);
    best_.resize(2 * n - 1);
    alive_flag_.assign(2 * n - 1, 0);
    for (uint32_t i = 0; i < n; ++i) {
      const Vpl& v = vpls[i];
      clusters_[i] = {v.position, v.position, std::max(luminance(v.intensity), weight_floor),
                      glm::normalize(v.normal), 0.0f};
      alive_.push_back(i);
      alive_flag_[i] = 1;
    }
  }

  // Runs the n-1 merges; `on_merge(new_id, a, b)` is told each one in order.
  template <class F>
  void run(F&& on_merge) {
    search_all();
    uint32_t next = uint32_t(alive_.size());
    while (alive_.size() > 1) {
      HeapEntry top = heap_.top();
      heap_.pop();
      uint32_t a = top.self, b = top.candidate.partner;
      if (!alive_flag_[a] || !alive_flag_[b] || best_[a].partner != b || best_[a].metric != top.candidate.metric)
        continue;  // stale: a or b merged since, or a found another partner
      merge(a, b, next);
      on_merge(next, a, b);
      research(a, b, next);
      ++next;
    }
  }

 private:
  Candidate search(uint32_t self) const {
    auto consider = [&](size_t begin, size_t end, Candidate best) {
      for (size_t k = begin; k < end; ++k) {
        uint32_t other = alive_[k];
        if (other == self) continue;
        // A pruned candidate reports a value > best.metric, so it cannot win or tie.
        Candidate c{metric_(clusters_[self], clusters_[other], best.metric), self > other ? self - other : other - self,
                    other};
        if (c < best) best = c;
      }
      return best;
    };
    if (alive_.size() < 4096) return consider(0, alive_.size(), Candidate{});
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, alive_.size(), 1024), Candidate{},
        [&](const tbb::blocked_range<size_t>& r, Candidate best) { return consider(r.begin(), r.end(), best); },
        [](const Candidate& x, const Candidate& y) { return y < x ? y : x; });
  }

  void search_many(const std::vector<uint32_t>& selves) {
    tbb::parallel_for(size_t(0), selves.size(), [&](size_t k) { best_[selves[k]] = search(selves[k]); });
    for (uint32_t s : selves) heap_.push({best_[s], s});
  }

  void search_all() { search_many(alive_); }

  void merge(uint32_t a, uint32_t b, uint32_t id) {
    const Cluster &ca = clusters_[a], &cb = clusters_[b];
    float theta = union_angle(ca, cb);
    clusters_[id] = {glm::min(ca.lo, cb.lo), glm::max(ca.hi, cb.hi), ca.weight + cb.weight,
                     union_axis(ca, cb, theta), theta};
    alive_flag_[a] = alive_flag_[b] = 0;
    alive_flag_[id] = 1;
    std::erase_if(alive_, [&](uint32_t c) { return c == a || c == b; });
    alive_.push_back(id);
  }

  void research(uint32_t a, uint32_t b, uint32_t id) {
    std::vector<uint32_t> selves{id};
    for (uint32_t c : alive_)
      if (c != id && (best_[c].partner == a || best_[c].partner == b)) selves.push_back(c);
    if (alive_.size() > 1) search_many(selves);
  }

  Metric metric_;
  std::vector<Cluster> clusters_;
  std::vector<Candidate> best_;
  std::vector<uint8_t> alive_flag_;
  std::vector<uint32_t> alive_;
  std::priority_queue<HeapEntry, std::vector<HeapEntry>, std::greater<HeapEntry>> heap_;
};

// Black VPLs would all have metric 0; a floor far below any real weight lets them cluster by
// size instead.
float weight_floor(const VplSet& vpls) {
  double total = 0.0;
  for (const Vpl& v : vpls) total += luminance(v.intensity);
  return total > 0.0 ? float(1e-6 * total / double(vpls.size())) : 1.0f;
}

}  // namespace

void build_agglomerative_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, float length_scale,
                              bool store, LightTree& tree) {
  const size_t n = vpls.size();
  if (n > kMaxAgglomerativeVpls)
    throw Error("light tree: tree 'agglomerative' is O(n^2) and limited to " + std::to_string(kMaxAgglomerativeVpls) +
                " VPLs, got " + std::to_string(n) + " (use tree 'radix' or 'perfect')");
  set_leaf_source(vpls, thresholds, tree);
  resize_uninitialized(tree.nodes, n == 0 ? 0 : n - 1, /*huge_pages=*/false);
  tree.stored_nodes = uint32_t(tree.nodes.size());
  tree.leaf_keys.resize(n);
  for (uint32_t i = 0; i < n; ++i) tree.leaf_keys[i] = i;  // leaf i is VPL i
  tree.root = n == 0 ? kNoNode : 0;
  tree.first_leaf = n == 0 ? 0 : uint32_t(n - 1);
  tree.leaf_count = uint32_t(n);
  if (n > 1) {
    // Cluster ids: VPL i is cluster i; the merge that makes cluster n + s is the s-th. Node
    // indices put the last merge (the root) at 0 and leaf i at n-1+i.
    auto node_of = [n](uint32_t cluster) { return cluster < n ? uint32_t(n - 1 + cluster) : uint32_t(2 * n - 2 - cluster); };
    Clustering clustering(vpls, length_scale, weight_floor(vpls));
    clustering.run([&](uint32_t id, uint32_t a, uint32_t b) {
      uint32_t na = node_of(a), nb = node_of(b);
      tree.nodes[node_of(id)] = merge_children(tree.node(na), na, tree.node(nb), nb, thresholds);
    });
  }
  if (store) store_leaves(tree);
}

}  // namespace sst
