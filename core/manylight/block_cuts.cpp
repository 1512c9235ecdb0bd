#include "core/manylight/block_cuts.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/shading/surface.h"

namespace sst {

namespace {
struct Candidate {
  uint32_t node;
  float error, intensity;
  bool operator<(const Candidate& o) const {
    return error != o.error ? error < o.error : intensity < o.intensity;
  }
};
}  // namespace

void build_cut(const LightTree& tree, uint32_t max_nodes, const NodeError& error, std::vector<uint32_t>& cut) {
  if (tree.empty() || max_nodes == 0) return;
  // Cuts are at most 32 nodes: a linear scan beats a heap.
  std::vector<Candidate> nodes;
  auto make = [&](uint32_t i) {
    const LightNode& n = tree[i];
    float e = n.is_leaf() ? 0.0f : error(n);
    return Candidate{i, std::isfinite(e) ? e : 0.0f, luminance(n.intensity)};
  };
  nodes.push_back(make(tree.root));
  for (;;) {
    if (nodes.size() >= max_nodes) break;
    int best = -1;
    for (size_t i = 0; i < nodes.size(); ++i)
      if (!tree[nodes[i].node].is_leaf() && (best < 0 || nodes[best] < nodes[i])) best = int(i);
    if (best < 0) break;  // only leaves left
    const LightNode& n = tree[nodes[best].node];
    uint32_t children[2] = {n.left, n.right};
    nodes.erase(nodes.begin() + best);
    // An empty child (perfect-tree padding) holds no VPL: leave it out of the cut.
    for (uint32_t c : children)
      if (!tree[c].empty()) nodes.push_back(make(c));
  }
  for (const Candidate& c : nodes) cut.push_back(c.node);
}

GBufferSample trace_gbuffer(const RenderContext& ctx, int x, int y) {
  GBufferSample g;
  Ray ray = ctx.camera.generate(float(x) + 0.5f, float(y) + 0.5f);
  Hit hit = ctx.accel.intersect(ray);
  if (!hit.valid()) return g;
  Surface s = make_surface(ctx.scene, hit, ray.direction);
  g.valid = true;
  g.p = s.p;
  g.n = s.ns;
  g.depth = glm::length(s.p - ray.origin);
  return g;
}

double BlockCuts::mean_size() const {
  uint64_t total = 0;
  for (uint32_t c : sizes) total += c;
  return sizes.empty() ? 0.0 : double(total) / double(sizes.size());
}

BlockCuts build_block_cuts(const RenderContext& ctx, const LightTree& tree, int block_size, uint32_t max_size,
                           const GuidePixel& guide_pixel, const GuidedError& error, const CutOrder& order) {
  BlockCuts cuts;
  cuts.grid = BlockGrid(ctx.width, ctx.height, block_size);
  cuts.max_size = max_size;
  cuts.nodes.assign(cuts.grid.count() * max_size, kNoNode);
  cuts.sizes.assign(cuts.grid.count(), 0);
  cuts.guides.assign(cuts.grid.count(), {});
  tbb::parallel_for(size_t(0), cuts.grid.count(), [&](size_t b) {
    BlockRect r;
    r.index = b;
    r.x0 = int(b % size_t(cuts.grid.blocks_x)) * block_size;
    r.y0 = int(b / size_t(cuts.grid.blocks_x)) * block_size;
    r.w = std::min(block_size, ctx.width - r.x0);
    r.h = std::min(block_size, ctx.height - r.y0);
    glm::ivec2 pixel = guide_pixel(r);
    const GBufferSample g = trace_gbuffer(ctx, pixel.x, pixel.y);
    cuts.guides[b] = g;
    std::vector<uint32_t> cut;
    cut.reserve(max_size);
    build_cut(tree, max_size, [&](const LightNode& node) { return error(node, g); }, cut);
    if (order) order(cut);
    std::copy(cut.begin(), cut.end(), cuts.nodes.begin() + b * max_size);
    cuts.sizes[b] = uint32_t(cut.size());
  });
  return cuts;
}

void set_cut_inputs(const BlockCuts& cuts, SamplerInputs& out) {
  out.cut_nodes = cuts.nodes;
  out.cut_sizes = cuts.sizes;
  out.params.cut_block_size = uint32_t(cuts.grid.block_size);
  out.params.cut_blocks_x = uint32_t(cuts.grid.blocks_x);
  out.params.cut_blocks_y = uint32_t(cuts.grid.blocks_y);
  out.params.cut_max_size = cuts.max_size;
  out.guides.resize(cuts.guides.size());
  for (size_t i = 0; i < cuts.guides.size(); ++i) {
    const GBufferSample& g = cuts.guides[i];
    out.guides[i] = {g.p, g.valid ? 1u : 0u, g.n, 0.0f};
  }
}

}  // namespace sst
