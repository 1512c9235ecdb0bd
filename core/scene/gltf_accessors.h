// The numbers of a glTF file: accessors read with every byte bounds-checked (tinygltf hands over
// offsets and lengths it has not checked), integers decoded by glTF's rules for normalized values,
// sparse substitution applied, and a primitive's KHR_draco_mesh_compression data handed to the
// Draco decoder (draco_mesh.h) once its bytes are checked. Geometry, animation and textures all
// read through this, none of them needing to know how a buffer's bytes become numbers.
#pragma once
#include <cstddef>
#include <initializer_list>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/scene/draco_mesh.h"
#include "core/scene/gltf_context.h"

namespace sst::gltf {

class Accessors {
 public:
  explicit Accessors(Context& ctx) : ctx_(ctx) {}

  // Without a bufferView nothing in the file bounds an accessor's count (its data is implicit
  // zeros), so the elements of all such accessors together are bounded before any is read: 40 of
  // them in a 4.6 KB file could otherwise ask for 30 GB.
  void check_implicit() const;

  const tinygltf::Accessor& accessor(int index, const std::string& what) const;

  // Start of `count` elements of `element` bytes, `stride` apart, at `offset` in a bufferView;
  // every byte is checked to lie inside the view and the view inside its buffer.
  const unsigned char* checked_bytes(int view_index, size_t offset, size_t element, size_t stride, size_t count,
                                     const std::string& what) const;

  // count x components numbers of an accessor, normalisation and sparse substitution applied.
  // T is float, double or uint32_t.
  template <class T>
  std::vector<T> read(int index, int components, const std::string& what) const;

  // Fails unless the accessor's componentType is one of `allowed` (with `normalized_only`, an
  // integer type counts only when normalized).
  void require_types(int index, std::initializer_list<int> allowed, bool normalized_only, const std::string& what) const;

  // A float attribute, checked to be finite. Decoded attributes are cached: meshes are often
  // instanced, and exporters let many primitives share one vertex accessor.
  const std::vector<float>& float_attribute(int index, int components, const std::string& semantic,
                                            const std::string& what);

  // The primitive's KHR_draco_mesh_compression data decoded (once per bufferView: instanced meshes
  // share it), or null without the extension.
  const DracoPrimitive* draco_primitive(const tinygltf::Primitive& prim, const std::string& what);

 private:
  template <class T>
  void apply_sparse(const tinygltf::Accessor& a, int size, int components, const std::string& where,
                    std::vector<T>& out) const;

  Context& ctx_;
  std::unordered_map<int, std::vector<float>> float_cache_;
  std::map<int, DracoPrimitive> draco_cache_;  // by bufferView
};

}  // namespace sst::gltf
