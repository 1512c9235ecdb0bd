#include "core/scene/gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/scene/gltf_extensions.h"

namespace sst::gltf {
namespace {

vec3 factor3(const Context& ctx, const std::vector<double>& v, size_t expected, vec3 fallback, const std::string& what) {
  if (v.empty()) return fallback;
  if (v.size() != expected)
    ctx.fail(what + " has " + std::to_string(v.size()) + " numbers (needs " + std::to_string(expected) + ")");
  if (!all_finite(v)) ctx.fail(what + " is not finite");
  return vec3(float(v[0]), float(v[1]), float(v[2]));
}

float unit_factor(Context& ctx, double v, const std::string& what) {
  if (!std::isfinite(v)) ctx.fail(what + " is not finite");
  if (v < 0.0 || v > 1.0) ctx.warnings.add(what + " outside [0, 1]: clamped");
  return float(std::clamp(v, 0.0, 1.0));
}

double emissive_strength(const tinygltf::Material& g) {
  const tinygltf::Value* ext = extension(g.extensions, "KHR_materials_emissive_strength");
  return number_or(ext ? member(*ext, "emissiveStrength") : nullptr, 1.0);
}

tinygltf::TextureInfo as_texture_info(const tinygltf::NormalTextureInfo& n) {
  tinygltf::TextureInfo t;
  t.index = n.index;
  t.texCoord = n.texCoord;
  t.extensions = n.extensions;
  return t;
}

// The UV set and KHR_texture_transform of one texture reference, checked.
UvMapping texture_uv_mapping(const Context& ctx, const tinygltf::TextureInfo& info, const std::string& what) {
  UvMapping m;
  m.set = info.texCoord;
  const tinygltf::Value* t = extension(info.extensions, "KHR_texture_transform");
  if (t) {
    auto pair = [&](const char* key, double fallback) {
      const tinygltf::Value* v = member(*t, key);
      if (v && (!v->IsArray() || v->ArrayLen() != 2)) ctx.fail(what + " has a KHR_texture_transform " + key + " that is not 2 numbers");
      return glm::dvec2(number_or(v ? &v->Get(0) : nullptr, fallback), number_or(v ? &v->Get(1) : nullptr, fallback));
    };
    const glm::dvec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
    const double rotation = number_or(member(*t, "rotation"), 0.0);
    if (!std::isfinite(offset.x + offset.y + scale.x + scale.y + rotation))
      ctx.fail(what + " has a non-finite KHR_texture_transform");
    if (const tinygltf::Value* set = member(*t, "texCoord")) {
      const double d = number_or(set, -1.0);  // checked before the conversion, which could overflow
      m.set = d >= 0.0 && d <= kMaxUvSet && d == std::floor(d) ? int(d) : -1;
    }
    // KHR_texture_transform: scale, then rotate (u' = u cos + v sin, v' = v cos - u sin), then offset.
    const double c = std::cos(rotation), s = std::sin(rotation);
    m.u = {scale.x * c, scale.y * s, offset.x};
    m.v = {-scale.x * s, scale.y * c, offset.y};
  }
  if (m.set < 0 || m.set > kMaxUvSet) ctx.fail(what + " has a texCoord that is not a whole number in 0.." + std::to_string(kMaxUvSet));
  return m;
}

}  // namespace

void Materials::build(Scene& scene) {
  std::vector<char> used(ctx_.model.materials.size() + 1, 0);
  for (uint32_t m : scene.triangle_material) used[m] = 1;
  for (size_t i = 0; i < ctx_.model.materials.size(); ++i) scene.materials.push_back(convert_material(int(i), used[i]));
  if (used.back()) {
    Material def;  // glTF's default material: white, metallic 1, roughness 1
    def.name = "default";
    scene.materials.push_back(def);
  }
}

Material Materials::convert_material(int index, bool used) {
  const tinygltf::Material& g = ctx_.model.materials[index];
  std::string what = "material '" + (g.name.empty() ? std::to_string(index) : g.name) + "'";
  const auto& pbr = g.pbrMetallicRoughness;
  Material out;
  out.name = g.name.empty() ? "material" + std::to_string(index) : g.name;
  vec3 base = factor3(ctx_, pbr.baseColorFactor, 4, vec3(1.0f), what + " baseColorFactor");
  if (glm::any(glm::lessThan(base, vec3(0.0f))) || glm::any(glm::greaterThan(base, vec3(1.0f))))
    ctx_.warnings.add(what + " baseColorFactor outside [0, 1]: clamped");
  out.base_color = glm::clamp(base, vec3(0.0f), vec3(1.0f));
  out.metallic = unit_factor(ctx_, pbr.metallicFactor, what + " metallicFactor");
  out.roughness = unit_factor(ctx_, pbr.roughnessFactor, what + " roughnessFactor");
  out.emission = factor3(ctx_, g.emissiveFactor, 3, vec3(0.0f), what + " emissiveFactor") * float(emissive_strength(g));
  if (!is_finite(out.emission) || glm::any(glm::lessThan(out.emission, vec3(0.0f))))
    ctx_.fail(what + " has a negative or non-finite emission (emissiveFactor * emissiveStrength)");
  out.double_sided = g.doubleSided;
  out.alpha = pbr.baseColorFactor.size() == 4 ? unit_factor(ctx_, pbr.baseColorFactor[3], what + " baseColorFactor alpha") : 1.0f;
  if (g.alphaMode == "MASK") {
    out.alpha_mode = AlphaMode::Mask;
    if (!std::isfinite(g.alphaCutoff) || g.alphaCutoff < 0.0)
      ctx_.fail(what + " has alphaCutoff " + std::to_string(g.alphaCutoff) + " (must be a number >= 0)");
    out.alpha_cutoff = float(g.alphaCutoff);
  } else if (g.alphaMode == "BLEND") {
    out.alpha_mode = AlphaMode::Blend;
  } else if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
    ctx_.fail(what + " has alphaMode '" + g.alphaMode + "' (must be OPAQUE, MASK or BLEND)");
  }
  if (used && out.alpha_mode != AlphaMode::Opaque)
    ctx_.uses.insert(out.alpha_mode == AlphaMode::Mask ? "alphaMode MASK" : "alphaMode BLEND (as a cutout at 0.5)");
  if (used) attach_textures(g, what, out);
  return out;
}

void Materials::attach_textures(const tinygltf::Material& g, const std::string& what, Material& out) {
  if (g.occlusionTexture.index >= 0) ctx_.warnings.add("occlusion textures are ignored (they model what GI computes)");
  const std::vector<std::string>& used = ctx_.model.extensionsUsed;
  for (const auto& [name, value] : g.extensions)  // those in extensionsUsed were reported already
    if (!implemented_extension(name) && std::find(used.begin(), used.end(), name) == used.end())
      ctx_.warnings.add("material extension " + name + " ignored");
  const auto& pbr = g.pbrMetallicRoughness;
  out.base_color_texture = texture_slot(pbr.baseColorTexture, true, what + " baseColorTexture");
  out.metallic_roughness_texture = texture_slot(pbr.metallicRoughnessTexture, false, what + " metallicRoughnessTexture");
  out.emissive_texture = texture_slot(g.emissiveTexture, true, what + " emissiveTexture");
  out.normal_texture = texture_slot(as_texture_info(g.normalTexture), false, what + " normalTexture");
  if (out.normal_texture >= 0) {
    if (!std::isfinite(g.normalTexture.scale)) ctx_.fail(what + " has a non-finite normalTexture scale");
    out.normal_scale = float(g.normalTexture.scale);
    ctx_.uses.insert("normalTexture");
  }
}

const UvMapping& Materials::uv_mapping(int gltf_material) {
  auto [it, fresh] = uv_mappings_.try_emplace(gltf_material);
  if (!fresh || gltf_material < 0 || size_t(gltf_material) >= ctx_.model.materials.size()) return it->second;
  const tinygltf::Material& g = ctx_.model.materials[gltf_material];
  const std::string what = quoted_name("material", gltf_material, g.name);
  const tinygltf::TextureInfo normal = as_texture_info(g.normalTexture);
  const std::pair<const tinygltf::TextureInfo*, const char*> slots[] = {
      {&g.pbrMetallicRoughness.baseColorTexture, " baseColorTexture"},
      {&g.pbrMetallicRoughness.metallicRoughnessTexture, " metallicRoughnessTexture"},
      {&g.emissiveTexture, " emissiveTexture"},
      {&normal, " normalTexture"}};
  bool first = true;
  for (const auto& [info, slot] : slots) {
    if (info->index < 0) continue;
    UvMapping m = texture_uv_mapping(ctx_, *info, what + slot);
    if (first) it->second = m;
    else if (!(m == it->second))
      ctx_.warnings.add("textures of one material with different UV sets or transforms: the first's used for all");
    first = false;
  }
  if (!it->second.affine_identity()) ctx_.uses.insert("KHR_texture_transform");
  if (it->second.set > 0) ctx_.uses.insert("TEXCOORD_" + std::to_string(it->second.set));
  return it->second;
}

int Materials::texture_slot(const tinygltf::TextureInfo& info, bool srgb, const std::string& what) {
  if (info.index < 0) return -1;
  const tinygltf::Model& model = ctx_.model;
  if (size_t(info.index) >= model.textures.size()) ctx_.fail(what + " refers to missing texture " + std::to_string(info.index));
  const tinygltf::Texture& tex = model.textures[info.index];
  if (tex.source < 0) {
    ctx_.warnings.add("textures without a core image source (e.g. KTX2/WebP extensions) ignored");
    return -1;
  }
  if (size_t(tex.source) >= model.images.size()) ctx_.fail(what + " refers to missing image " + std::to_string(tex.source));
  if (tex.sampler >= int(model.samplers.size())) ctx_.fail(what + " refers to missing sampler " + std::to_string(tex.sampler));
  TextureKey key{tex.source, srgb, std::max(tex.sampler, -1)};
  auto [it, fresh] = texture_slots_.try_emplace(key, int(texture_keys_.size()));
  if (fresh) texture_keys_.push_back(key);
  return it->second;
}

}  // namespace sst::gltf
