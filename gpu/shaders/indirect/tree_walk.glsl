// The GLSL twin of the generic light-tree walk of core/manylight/slc_sampler.{h,cpp}
// (traverse_tree, divide_by_probability), shared by slc and sst: from the root, child i with
// probability w_i / (w_1 + w_2), until a leaf or (sst's diffuse lobe) a suitable node.
//
// Precision. The CPU keeps the weights and the path probability in double. Here the weights are
// float (their ratios, hence the choices, differ from the CPU's only at float ties; a weight
// outside float's range, lum(I) * bound / d^2 > 3e38, cannot occur at the scene scales the tool
// accepts). The path probability, a product of up to tree-height factors, is kept as a float
// mantissa and a power-of-two exponent (TreeProbability), so that it never underflows where the
// CPU's double does not: c / P is then formed as the CPU forms it, finite or not.
//
// Needs, before inclusion: the MANY_LIGHT_BUFFERS, ShadingPoint (indirect_sampler.glsl),
// sobol_sampler.glsl, and the weight functions below (declared here, defined in slc.glsl and
// sst.glsl).
#ifndef SST_GPU_SHADERS_INDIRECT_TREE_WALK_GLSL
#define SST_GPU_SHADERS_INDIRECT_TREE_WALK_GLSL

vec2 slc_child_weights(LightNode left, LightNode right, vec3 x, vec3 n);
float sst_node_weight(LightNode node, ShadingPoint sp, float eps, bool glossy);

// Which weights the walk uses, and where it stops.
#define TREE_WEIGHTS_SLC 0u
#define TREE_WEIGHTS_SST 1u
struct TreeWalk {
  uint weights;            // TREE_WEIGHTS_*
  float sst_eps;           // sst: the distance floor, in scene units
  bool sst_glossy;         // sst: the lobe (false: diffuse)
  bool stop_at_suitable;   // sst's diffuse lobe with substitutes
};

// A probability as m * 2^e, m renormalised whenever it falls below 2^-64.
struct TreeProbability {
  float m;
  int e;
};

TreeProbability tree_probability_one() { return TreeProbability(1.0, 0); }

TreeProbability tree_probability_times(TreeProbability p, float factor) {
  precise float m = p.m * factor;
  p.m = m;
  if (p.m > 0.0 && p.m < ldexp(1.0, -64)) {
    p.m = ldexp(p.m, 64);  // exact
    p.e -= 64;
  }
  return p;
}

bool tree_probability_positive(TreeProbability p) { return p.m > 0.0; }

// divide_by_probability: c / P; 0 for P <= 0, c <= 0, or a non-finite result (as the CPU's
// float(double(c) / P) is when it leaves float's range).
vec3 divide_by_probability(vec3 c, TreeProbability p) {
  if (!(p.m > 0.0) || max_component(c) <= 0.0) return vec3(0.0);
  precise vec3 q = c / p.m;
  // ldexp saturates to +inf (overflow) or 0 (underflow) like the double -> float conversion.
  vec3 v = vec3(ldexp(q.x, -p.e), ldexp(q.y, -p.e), ldexp(q.z, -p.e));
  return is_finite3(v) ? v : vec3(0.0);
}

struct TreeTraversal {
  uint node;  // the stop node; ML_NO_NODE: a dead branch
  TreeProbability probability;
  uint nodes_visited;  // nodes whose weights were evaluated, the root included
};

vec2 tree_child_weights(TreeWalk walk, LightNode left, LightNode right, ShadingPoint sp) {
  if (walk.weights == TREE_WEIGHTS_SLC) return slc_child_weights(left, right, sp.p, sp.basis.n);
  return vec2(sst_node_weight(left, sp, walk.sst_eps, walk.sst_glossy),
              sst_node_weight(right, sp, walk.sst_eps, walk.sst_glossy));
}

bool tree_walk_stops(TreeWalk walk, LightNode node) {
  if ((node.flags & ML_NODE_LEAF) != 0u) return true;
  return walk.stop_at_suitable && (node.flags & ML_NODE_SUITABLE) != 0u;
}

TreeTraversal traverse_tree(ShadingPoint sp, TreeWalk walk, inout PixelSampler ps) {
  TreeTraversal t;
  t.node = ML_NO_NODE;
  t.probability = TreeProbability(0.0, 0);
  t.nodes_visited = 0u;
  if (ml_params.tree_root == ML_NO_NODE) return t;
  uint i = ml_params.tree_root;
  TreeProbability p = tree_probability_one();
  // A walk visits at most every node once; the bound only guards against a malformed tree.
  for (uint step = 0u; step < ml_params.tree_node_count; ++step) {
    ++t.nodes_visited;
    LightNode node = ml_nodes[i];
    if (tree_walk_stops(walk, node)) {
      t.node = i;
      t.probability = p;
      return t;
    }
    vec2 w = tree_child_weights(walk, ml_nodes[node.left], ml_nodes[node.right], sp);
    float sum = w.x + w.y;
    if (!(sum > 0.0) || !is_finite(sum)) return t;  // dead branch: the sample is wasted
    float p_left = w.x / sum;
    // A child of weight 0 is never taken, and no uniform is drawn unless both can be.
    bool left = w.y <= 0.0 || (w.x > 0.0 && pixel_sampler_get1d(ps) < p_left);
    p = tree_probability_times(p, left ? p_left : w.y / sum);
    i = left ? node.left : node.right;
  }
  return t;
}

#endif
