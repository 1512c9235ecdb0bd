#include "core/scene/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace sst::gltf {
namespace {

constexpr size_t kMaxImplicitElements = size_t(1) << 24;

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

// Integers decode per the glTF rules for normalized values (signed ones clamp at -1).
double load_component(const unsigned char* p, int type, bool normalized) {
  auto get = [p](auto v) { std::memcpy(&v, p, sizeof v); return v; };
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: { double v = get(int8_t()); return normalized ? std::max(v / 127.0, -1.0) : v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { double v = get(uint8_t()); return normalized ? v / 255.0 : v; }
    case TINYGLTF_COMPONENT_TYPE_SHORT: { double v = get(int16_t()); return normalized ? std::max(v / 32767.0, -1.0) : v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { double v = get(uint16_t()); return normalized ? v / 65535.0 : v; }
    case TINYGLTF_COMPONENT_TYPE_INT: return get(int32_t());
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return get(uint32_t());
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return get(float());
    default: return 0.0;
  }
}

}  // namespace

const unsigned char* Accessors::checked_bytes(int view_index, size_t offset, size_t element, size_t stride,
                                              size_t count, const std::string& what) const {
  const tinygltf::Model& model = ctx_.model;
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    ctx_.fail(what + " refers to missing bufferView " + std::to_string(view_index));
  const tinygltf::BufferView& view = model.bufferViews[view_index];
  std::string view_name = "bufferView " + std::to_string(view_index);
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    ctx_.fail(view_name + " refers to missing buffer " + std::to_string(view.buffer));
  const tinygltf::Buffer& buffer = model.buffers[view.buffer];
  if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
    ctx_.fail("buffer " + std::to_string(view.buffer) + " is too short for " + view_name + " (needs " +
              std::to_string(view.byteOffset + view.byteLength) + " bytes, has " + std::to_string(buffer.data.size()) + ")");
  if (count > 0) {
    size_t len = view.byteLength;
    bool fits = offset <= len && element <= len - offset && (count - 1) <= (len - offset - element) / std::max<size_t>(stride, 1);
    if (!fits) {
      // In long double and printed from it: the sum may exceed 2^64 (a byteOffset of 2^64-1),
      // where a cast back to an integer is undefined.
      long double needed = (long double)offset + (long double)(count - 1) * stride + element;
      char needed_text[64];
      std::snprintf(needed_text, sizeof needed_text, "%.0Lf", needed);
      ctx_.fail(what + " reaches beyond " + view_name + " (needs " + needed_text + " bytes, has " + std::to_string(len) + ")");
    }
  }
  return buffer.data.data() + view.byteOffset + offset;
}

const tinygltf::Accessor& Accessors::accessor(int index, const std::string& what) const {
  if (index < 0 || size_t(index) >= ctx_.model.accessors.size())
    ctx_.fail(what + " refers to missing accessor " + std::to_string(index));
  return ctx_.model.accessors[index];
}

void Accessors::check_implicit() const {
  size_t total = 0;
  for (size_t i = 0; i < ctx_.model.accessors.size(); ++i) {
    const tinygltf::Accessor& a = ctx_.model.accessors[i];
    if (a.bufferView >= 0) continue;
    total += std::min(a.count, kMaxImplicitElements + 1);
    if (total > kMaxImplicitElements)
      ctx_.fail("accessor " + std::to_string(i) + " has no bufferView and count " + std::to_string(a.count) +
                ": accessors without data may hold at most " + std::to_string(kMaxImplicitElements) + " elements in all");
  }
}

template <class T>
std::vector<T> Accessors::read(int index, int components, const std::string& what) const {
  const tinygltf::Accessor& a = accessor(index, what);
  std::string where = what + " (accessor " + std::to_string(index) + ")";
  int size = component_size(a.componentType);
  if (size == 0) ctx_.fail(where + " has invalid componentType " + std::to_string(a.componentType));
  if (tinygltf::GetNumComponentsInType(a.type) != components)
    ctx_.fail(where + " has " + std::to_string(tinygltf::GetNumComponentsInType(a.type)) + " components per element (needs " +
              std::to_string(components) + ")");
  size_t element = size_t(size) * components;
  // (An accessor without a bufferView has a count bounded by check_implicit.)
  const unsigned char* p = nullptr;
  size_t stride = element;
  if (a.bufferView >= 0) {
    if (size_t(a.bufferView) < ctx_.model.bufferViews.size() && ctx_.model.bufferViews[a.bufferView].byteStride > 0)
      stride = ctx_.model.bufferViews[a.bufferView].byteStride;
    p = checked_bytes(a.bufferView, a.byteOffset, element, stride, a.count, where);
  }
  std::vector<T> out(a.count * components, T(0));
  if (p) {
    for (size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < components; ++c)
        out[i * components + c] = T(load_component(p + i * stride + size_t(c) * size, a.componentType, a.normalized));
  }
  if (a.sparse.isSparse) apply_sparse(a, size, components, where, out);
  return out;
}

template <class T>
void Accessors::apply_sparse(const tinygltf::Accessor& a, int size, int components, const std::string& where,
                             std::vector<T>& out) const {
  if (a.sparse.count < 0) ctx_.fail(where + " has a negative sparse count");
  size_t n = size_t(a.sparse.count);
  int index_type = a.sparse.indices.componentType;
  int index_size = component_size(index_type);
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    ctx_.fail(where + " has sparse indices of invalid componentType " + std::to_string(index_type));
  if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) ctx_.fail(where + " has a negative sparse byteOffset");
  size_t element = size_t(size) * components;
  const unsigned char* idx = checked_bytes(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, index_size,
                                           index_size, n, where + " sparse indices");
  const unsigned char* val = checked_bytes(a.sparse.values.bufferView, a.sparse.values.byteOffset, element, element, n,
                                           where + " sparse values");
  for (size_t k = 0; k < n; ++k) {
    double target = load_component(idx + k * index_size, index_type, false);
    if (target >= double(a.count))
      ctx_.fail(where + " sparse index " + std::to_string((unsigned long long)target) + " >= count " + std::to_string(a.count));
    for (int c = 0; c < components; ++c)
      out[size_t(target) * components + c] =
          T(load_component(val + k * element + size_t(c) * size, a.componentType, a.normalized));
  }
}

void Accessors::require_types(int index, std::initializer_list<int> allowed, bool normalized_only,
                              const std::string& what) const {
  const tinygltf::Accessor& a = accessor(index, what);
  for (int t : allowed)
    if (a.componentType == t && (!normalized_only || a.normalized || t == TINYGLTF_COMPONENT_TYPE_FLOAT)) return;
  ctx_.fail(what + " (accessor " + std::to_string(index) + ") has unsupported componentType " +
            std::to_string(a.componentType) + (a.normalized ? " (normalized)" : ""));
}

const std::vector<float>& Accessors::float_attribute(int index, int components, const std::string& semantic,
                                                     const std::string& what) {
  auto it = float_cache_.find(index);
  if (it != float_cache_.end()) return it->second;
  std::vector<float> values = read<float>(index, components, what + " " + semantic);
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      ctx_.fail(what + " " + semantic + " has a non-finite value (NaN or Inf) at vertex " + std::to_string(i / components));
  return float_cache_.emplace(index, std::move(values)).first->second;
}

const DracoPrimitive* Accessors::draco_primitive(const tinygltf::Primitive& prim, const std::string& what) {
  const tinygltf::Value* ext = extension(prim.extensions, "KHR_draco_mesh_compression");
  if (!ext) return nullptr;
  const double view = number_or(member(*ext, "bufferView"), -1.0);
  const tinygltf::Value* attributes = member(*ext, "attributes");
  if (!(view >= 0.0 && view < double(ctx_.model.bufferViews.size()) && view == std::floor(view)))
    ctx_.fail(what + " has a KHR_draco_mesh_compression without a valid bufferView");
  if (!attributes || !attributes->IsObject())
    ctx_.fail(what + " has a KHR_draco_mesh_compression without attributes");
  const int view_index = int(view);
  if (auto it = draco_cache_.find(view_index); it != draco_cache_.end()) return &it->second;
  std::map<std::string, DracoAttributeRequest> requests;
  for (const std::string& semantic : attributes->Keys()) {
    const double id = number_or(&attributes->Get(semantic), -1.0);
    if (!(id >= 0.0 && id <= double(INT32_MAX) && id == std::floor(id)))
      ctx_.fail(what + " has a KHR_draco_mesh_compression attribute " + semantic + " that is not a whole number");
    DracoAttributeRequest& r = requests[semantic];
    r.unique_id = int(id);
    if (auto a = prim.attributes.find(semantic); a != prim.attributes.end())
      r.normalized = accessor(a->second, what + " " + semantic).normalized;
  }
  const size_t length = ctx_.model.bufferViews[view_index].byteLength;
  const unsigned char* bytes = checked_bytes(view_index, 0, length, 1, 1, what + " Draco data");
  ctx_.uses.insert("KHR_draco_mesh_compression");
  return &draco_cache_.emplace(view_index, decode_draco_primitive(bytes, length, requests, ctx_.file + ": " + what))
              .first->second;
}

template std::vector<float> Accessors::read<float>(int, int, const std::string&) const;
template std::vector<double> Accessors::read<double>(int, int, const std::string&) const;
template std::vector<uint32_t> Accessors::read<uint32_t>(int, int, const std::string&) const;

}  // namespace sst::gltf
