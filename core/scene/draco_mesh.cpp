#include "core/scene/draco_mesh.h"

#include <draco/compression/decode.h>

#include <limits>

#include "core/util/error.h"

namespace sst {
namespace {

// The largest value of an integer Draco type (what a normalized value divides by), 0 for floats.
double integer_max(draco::DataType type) {
  switch (type) {
    case draco::DT_INT8: return std::numeric_limits<int8_t>::max();
    case draco::DT_UINT8: return std::numeric_limits<uint8_t>::max();
    case draco::DT_INT16: return std::numeric_limits<int16_t>::max();
    case draco::DT_UINT16: return std::numeric_limits<uint16_t>::max();
    case draco::DT_INT32: return std::numeric_limits<int32_t>::max();
    case draco::DT_UINT32: return std::numeric_limits<uint32_t>::max();
    default: return 0.0;
  }
}

}  // namespace

DracoPrimitive decode_draco_primitive(const unsigned char* bytes, size_t size,
                                      const std::map<std::string, DracoAttributeRequest>& requests,
                                      const std::string& what) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), size);
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
    throw Error(what + ": the KHR_draco_mesh_compression data is not a Draco triangle mesh" +
                (type.ok() ? "" : " (" + type.status().error_msg_string() + ")"));
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    throw Error(what + ": Draco could not decode the mesh (" + decoded.status().error_msg_string() + ")");
  const draco::Mesh& mesh = *decoded.value();

  DracoPrimitive out;
  out.points = mesh.num_points();
  out.indices.reserve(size_t(mesh.num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t index = mesh.face(f)[k].value();
      if (index >= out.points)
        throw Error(what + ": Draco face " + std::to_string(f.value()) + " names point " + std::to_string(index) +
                    " of " + std::to_string(out.points));
      out.indices.push_back(index);
    }

  for (const auto& [semantic, request] : requests) {
    const draco::PointAttribute* attribute =
        request.unique_id >= 0 ? mesh.GetAttributeByUniqueId(uint32_t(request.unique_id)) : nullptr;
    if (!attribute)
      throw Error(what + ": the Draco mesh has no attribute " + std::to_string(request.unique_id) + " (" + semantic +
                  ")");
    const int components = attribute->num_components();
    if (components < 1 || components > 4)
      throw Error(what + ": Draco attribute " + semantic + " has " + std::to_string(components) + " components");
    // Integers of an accessor marked normalized map to [0, 1] (signed: [-1, 1]) whether or not
    // the encoder marked the Draco attribute so.
    const double scale =
        request.normalized && !attribute->normalized() && integer_max(attribute->data_type()) > 0.0
            ? 1.0 / integer_max(attribute->data_type())
            : 1.0;
    std::vector<float>& values = out.attributes[semantic];
    values.resize(out.points * size_t(components));
    for (uint32_t p = 0; p < out.points; ++p) {
      float* v = values.data() + size_t(p) * size_t(components);
      if (!attribute->ConvertValue<float>(attribute->mapped_index(draco::PointIndex(p)), int8_t(components), v))
        throw Error(what + ": Draco attribute " + semantic + " cannot be read as numbers");
      for (int c = 0; c < components; ++c) v[c] = float(double(v[c]) * scale);
    }
    out.components[semantic] = components;
  }
  return out;
}

}  // namespace sst
