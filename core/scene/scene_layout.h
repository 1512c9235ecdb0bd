// The scene as the shared kernels read it (core/shading/surface_eval.h,
// core/scene/texture_sample.h) and as it crosses the host/GPU boundary (Vulkan backend), defined
// once for C++ and GLSL. In C++ the structures live in namespace sst::glsl (also named in sst) and
// are built from glm types, with static_asserts on size and offsets; in GLSL the same text
// declares plain structs for std430 buffers (include with GL_GOOGLE_include_directive). On the CPU
// the kernels' hooks convert a sst::Scene's arrays element by element (core/scene/scene_access.h);
// for the GPU gpu/scene_upload.h packs them (pack_scene) and gpu/shaders/surface.glsl binds the
// hooks to the buffers.
//
// Five std430 storage buffers (no vec3 arrays: every vec3 is followed by a 4-byte scalar, which
// std430 packs into the vec3's 16-byte slot, exactly like the C++ layout). A shader declares them
// with SCENE_BUFFERS(first_binding) (GLSL only, below) under these names:
//   SceneVertex   scene_vertices[]   64 bytes each, Scene::positions/normals/uvs/tangents/colors[i]
//                                    at index i.
//   SceneTriangle scene_triangles[]  16 bytes each, Scene::triangles/triangle_material[i] at i.
//   SceneMaterial scene_materials[]  64 bytes each, Scene::materials[i] at index i.
//   SceneTexture  scene_textures[]   32 bytes each, Scene::textures[i] at index i.
//   uint          scene_texels[]     the 8-bit decoding tables (SCENE_TEXELS_*_TABLE), then the
//                                    texels of all textures, one after the other (see
//                                    SceneTexture.texel_offset and .format).
// An empty array is still bound as a small dummy buffer (Vulkan has no empty buffers); indices
// into it are never produced.
#ifndef SST_CORE_SCENE_SCENE_LAYOUT_H
#define SST_CORE_SCENE_SCENE_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
using glm::vec4;
#endif

// SceneTexture.wrap_s / wrap_t: the glTF sampler's wrap modes (sst::Wrap).
#define SCENE_WRAP_REPEAT 0u
#define SCENE_WRAP_CLAMP_TO_EDGE 1u
#define SCENE_WRAP_MIRRORED_REPEAT 2u

// SceneTexture.format: how the texture's texels are stored in scene_texels[].
//   RGBA8       one uint a texel, R in the low byte; every channel linear (c * (1.0f / 255.0f)).
//   RGBA8_SRGB  one uint a texel; R, G, B sRGB-encoded (decoded through SCENE_SRGB_DECODE_BITS),
//               alpha linear (SCENE_UNORM8_BITS).
//   RGBA32F     four uints a texel: the bits of linear R, G, B, A floats (16-bit images).
#define SCENE_TEXTURE_RGBA8 0u
#define SCENE_TEXTURE_RGBA8_SRGB 1u
#define SCENE_TEXTURE_RGBA32F 2u

// One vertex: Scene::positions[i], Scene::normals[i] and Scene::uvs[i] (zero when the scene has
// no uvs), the uv split over the two scalar slots, Scene::tangents[i] and Scene::colors[i] (their
// defaults when the scene has none).
struct SceneVertex {
  vec3 position;  // world space
  float u;        // Scene::uvs[i].x
  vec3 normal;    // the vertex (shading) normal as the scene stores it (unit, or zero)
  float v;        // Scene::uvs[i].y
  vec4 tangent;   // glTF TANGENT: unit xyz and the bitangent's sign w; zero: derived from the uvs
  vec4 color;     // glTF COLOR_0, linear RGBA; 1 without one
};

// One triangle: Scene::triangles[i] (indices into scene_vertices[], in winding order: the
// geometric normal is cross(v1 - v0, v2 - v0)) and Scene::triangle_material[i].
struct SceneTriangle {
  uint v0;
  uint v1;
  uint v2;
  uint material;  // index into scene_materials[]
};

// One glTF metallic-roughness material (sst::Material). Texture indices are -1 when absent;
// Indices beyond the texture table are -1 too (scene_texture_index), so the kernels only test >= 0.
struct SceneMaterial {
  vec3 base_color;                 // linear RGB factor, multiplied by the base-colour texture
  float metallic;                  // factor, multiplied by the metallic-roughness texture's B
  vec3 emission;                   // emitted radiance (emissiveFactor * strength), x texture
  float roughness;                 // factor, multiplied by the metallic-roughness texture's G
  int base_color_texture;          // index into scene_textures[], or -1
  int metallic_roughness_texture;  // index into scene_textures[], or -1 (G = roughness, B = metallic)
  int emissive_texture;            // index into scene_textures[], or -1
  uint double_sided;               // 1: emits (and is lit) on both sides; 0: front only
  float alpha;                     // baseColorFactor's alpha, x the base-colour texture's and COLOR_0's
  float alpha_cutoff;              // a hit counts where alpha >= alpha_cutoff; 0: opaque (all count)
  int normal_texture;              // index into scene_textures[], or -1 (tangent-space normal map)
  float normal_scale;              // glTF normalTexture.scale: scales the map's x and y
};

// One texture (sst::Texture): row 0 at the top, sampled bilinearly (or nearest) with its wrap
// modes and no mip-mapping. Texel (x, y) is at scene_texels[texel_offset + (y * width + x)] for
// the 8-bit formats and at scene_texels[texel_offset + 4 * (y * width + x) + c] for RGBA32F.
struct SceneTexture {
  uint texel_offset;  // index of the first texel's first uint in scene_texels[]
  int width;          // texels; a texture of width or height 0 samples as vec4(1)
  int height;
  uint format;        // SCENE_TEXTURE_*
  uint wrap_s;        // SCENE_WRAP_*, along u (x)
  uint wrap_t;        // SCENE_WRAP_*, along v (y)
  uint nearest;       // 1: glTF magFilter NEAREST (nearest texel); 0: bilinear
  uint reserved;      // 0
};

// The 8-bit decoding tables of core/scene/texture_sample.h as float bits, so that both backends
// decode texels to the same floats (no pow, no division):
//   SCENE_SRGB_DECODE_BITS[i] = bits of srgb_decode(float(i) / 255.0f) (core/image/image.h)
//   SCENE_UNORM8_BITS[i]      = bits of float(i) / 255.0f (the alpha of 8-bit texels)
// tests/gpu/scene_upload_test.cpp checks both against the C++ functions. They travel at the start
// of scene_texels[] (words SCENE_TEXELS_SRGB_TABLE.. and SCENE_TEXELS_UNORM8_TABLE..), not as GLSL
// const arrays: a dynamically indexed const array becomes a 256-way branch ladder in lavapipe.
// The first texture's texels start at SCENE_TEXELS_FIRST_TEXEL.
#define SCENE_TEXELS_SRGB_TABLE 0u
#define SCENE_TEXELS_UNORM8_TABLE 256u
#define SCENE_TEXELS_FIRST_TEXEL 512u
#define SCENE_SRGB_DECODE_BITS \
  0x00000000u, 0x399F22B4u, 0x3A1F22B4u, 0x3A6EB40Eu, 0x3A9F22B4u, 0x3AC6EB61u, 0x3AEEB40Eu, 0x3B0B3E5Du, \
  0x3B1F22B4u, 0x3B33070Bu, 0x3B46EB61u, 0x3B5B518Au, 0x3B70F18Au, 0x3B83E1C5u, 0x3B8FE614u, 0x3B9C87FBu, \
  0x3BA9C9B5u, 0x3BB7AD6Du, 0x3BC63547u, 0x3BD5635Fu, 0x3BE539BDu, 0x3BF5BA70u, 0x3C0373B5u, 0x3C0C6152u, \
  0x3C15A703u, 0x3C1F45BCu, 0x3C293E68u, 0x3C3391F4u, 0x3C3E4149u, 0x3C494D43u, 0x3C54B6C7u, 0x3C607EB1u, \
  0x3C6CA5DFu, 0x3C792D22u, 0x3C830AA8u, 0x3C89AF9Fu, 0x3C9085DBu, 0x3C978DC5u, 0x3C9EC7C0u, 0x3CA63431u, \
  0x3CADD37Du, 0x3CB5A601u, 0x3CBDAC20u, 0x3CC5E639u, 0x3CCE54ABu, 0x3CD6F7D3u, 0x3CDFD00Eu, 0x3CE8DDB9u, \
  0x3CF2212Cu, 0x3CFB9AC1u, 0x3D02A569u, 0x3D0798DCu, 0x3D0CA7E4u, 0x3D11D2AEu, 0x3D171963u, 0x3D1C7C2Eu, \
  0x3D21FB39u, 0x3D2796AFu, 0x3D2D4EBBu, 0x3D332380u, 0x3D39152Bu, 0x3D3F23E3u, 0x3D454FD1u, 0x3D4B991Cu, \
  0x3D51FFEBu, 0x3D588466u, 0x3D5F26B7u, 0x3D65E6FEu, 0x3D6CC564u, 0x3D73C20Fu, 0x3D7ADD25u, 0x3D810B66u, \
  0x3D84B793u, 0x3D88732Eu, 0x3D8C3E48u, 0x3D9018F4u, 0x3D940343u, 0x3D97FD48u, 0x3D9C0714u, 0x3DA020B9u, \
  0x3DA44A49u, 0x3DA883D7u, 0x3DACCD70u, 0x3DB12728u, 0x3DB59110u, 0x3DBA0B38u, 0x3DBE95B3u, 0x3DC3308Fu, \
  0x3DC7DBE0u, 0x3DCC97B4u, 0x3DD1641Cu, 0x3DD6412Au, 0x3DDB2EEDu, 0x3DE02D75u, 0x3DE53CD3u, 0x3DEA5D16u, \
  0x3DEF8E52u, 0x3DF4D091u, 0x3DFA23E5u, 0x3DFF885Eu, 0x3E027F06u, 0x3E05427Fu, 0x3E080EA2u, 0x3E0AE376u, \
  0x3E0DC104u, 0x3E10A752u, 0x3E139669u, 0x3E168E50u, 0x3E198F0Eu, 0x3E1C98ABu, 0x3E1FAB2Fu, 0x3E22C6A0u, \
  0x3E25EB07u, 0x3E29186Au, 0x3E2C4ED0u, 0x3E2F8E41u, 0x3E32D6C4u, 0x3E362861u, 0x3E39831Eu, 0x3E3CE703u, \
  0x3E405416u, 0x3E43CA5Fu, 0x3E4749E4u, 0x3E4AD2AEu, 0x3E4E64C2u, 0x3E520027u, 0x3E55A4E6u, 0x3E595303u, \
  0x3E5D0A8Bu, 0x3E60CB7Cu, 0x3E6495E0u, 0x3E6869BFu, 0x3E6C4720u, 0x3E702E08u, 0x3E741E7Fu, 0x3E78188Cu, \
  0x3E7C1C34u, 0x3E8014BFu, 0x3E822039u, 0x3E84308Bu, 0x3E8645B8u, 0x3E885FC3u, 0x3E8A7EB0u, 0x3E8CA281u, \
  0x3E8ECB3Au, 0x3E90F8DFu, 0x3E932B72u, 0x3E9562F6u, 0x3E979F6Fu, 0x3E99E0E0u, 0x3E9C274Eu, 0x3E9E72B7u, \
  0x3EA0C322u, 0x3EA31892u, 0x3EA57308u, 0x3EA7D289u, 0x3EAA3718u, 0x3EACA0B7u, 0x3EAF0F69u, 0x3EB18333u, \
  0x3EB3FC16u, 0x3EB67A15u, 0x3EB8FD34u, 0x3EBB8576u, 0x3EBE12DEu, 0x3EC0A56Eu, 0x3EC33D2Au, 0x3EC5DA14u, \
  0x3EC87C30u, 0x3ECB2380u, 0x3ECDD008u, 0x3ED081CAu, 0x3ED338C9u, 0x3ED5F508u, 0x3ED8B68Au, 0x3EDB7D51u, \
  0x3EDE4962u, 0x3EE11ABEu, 0x3EE3F168u, 0x3EE6CD64u, 0x3EE9AEB6u, 0x3EEC955Du, 0x3EEF815Du, 0x3EF272BAu, \
  0x3EF56976u, 0x3EF86594u, 0x3EFB6717u, 0x3EFE6E02u, 0x3F00BD2Bu, 0x3F02460Cu, 0x3F03D1A5u, 0x3F055FF8u, \
  0x3F06F105u, 0x3F0884CEu, 0x3F0A1B54u, 0x3F0BB499u, 0x3F0D509Fu, 0x3F0EEF65u, 0x3F1090EFu, 0x3F12353Du, \
  0x3F13DC50u, 0x3F15862Au, 0x3F1732CCu, 0x3F18E237u, 0x3F1A946Du, 0x3F1C4970u, 0x3F1E013Fu, 0x3F1FBBDEu, \
  0x3F21794Cu, 0x3F23398Cu, 0x3F24FCA0u, 0x3F26C286u, 0x3F288B41u, 0x3F2A56D3u, 0x3F2C253Du, 0x3F2DF680u, \
  0x3F2FCA9Cu, 0x3F31A195u, 0x3F337B6Au, 0x3F35581Eu, 0x3F3737B1u, 0x3F391A24u, 0x3F3AFF7Au, 0x3F3CE7B3u, \
  0x3F3ED2D0u, 0x3F40C0D2u, 0x3F42B1BCu, 0x3F44A58Eu, 0x3F469C49u, 0x3F4895EFu, 0x3F4A9280u, 0x3F4C91FFu, \
  0x3F4E946Cu, 0x3F5099C8u, 0x3F52A216u, 0x3F54AD55u, 0x3F56BB87u, 0x3F58CCAEu, 0x3F5AE0CBu, 0x3F5CF7DEu, \
  0x3F5F11ECu, 0x3F612EF0u, 0x3F634EEFu, 0x3F6571E9u, 0x3F6797E1u, 0x3F69C0D6u, 0x3F6BECCBu, 0x3F6E1BBFu, \
  0x3F704DB6u, 0x3F7282AFu, 0x3F74BAACu, 0x3F76F5AEu, 0x3F7933B6u, 0x3F7B74C6u, 0x3F7DB8DEu, 0x3F800000u
#define SCENE_UNORM8_BITS \
  0x00000000u, 0x3B808081u, 0x3C008081u, 0x3C40C0C1u, 0x3C808081u, 0x3CA0A0A1u, 0x3CC0C0C1u, 0x3CE0E0E1u, \
  0x3D008081u, 0x3D109091u, 0x3D20A0A1u, 0x3D30B0B1u, 0x3D40C0C1u, 0x3D50D0D1u, 0x3D60E0E1u, 0x3D70F0F1u, \
  0x3D808081u, 0x3D888889u, 0x3D909091u, 0x3D989899u, 0x3DA0A0A1u, 0x3DA8A8A9u, 0x3DB0B0B1u, 0x3DB8B8B9u, \
  0x3DC0C0C1u, 0x3DC8C8C9u, 0x3DD0D0D1u, 0x3DD8D8D9u, 0x3DE0E0E1u, 0x3DE8E8E9u, 0x3DF0F0F1u, 0x3DF8F8F9u, \
  0x3E008081u, 0x3E048485u, 0x3E088889u, 0x3E0C8C8Du, 0x3E109091u, 0x3E149495u, 0x3E189899u, 0x3E1C9C9Du, \
  0x3E20A0A1u, 0x3E24A4A5u, 0x3E28A8A9u, 0x3E2CACADu, 0x3E30B0B1u, 0x3E34B4B5u, 0x3E38B8B9u, 0x3E3CBCBDu, \
  0x3E40C0C1u, 0x3E44C4C5u, 0x3E48C8C9u, 0x3E4CCCCDu, 0x3E50D0D1u, 0x3E54D4D5u, 0x3E58D8D9u, 0x3E5CDCDDu, \
  0x3E60E0E1u, 0x3E64E4E5u, 0x3E68E8E9u, 0x3E6CECEDu, 0x3E70F0F1u, 0x3E74F4F5u, 0x3E78F8F9u, 0x3E7CFCFDu, \
  0x3E808081u, 0x3E828283u, 0x3E848485u, 0x3E868687u, 0x3E888889u, 0x3E8A8A8Bu, 0x3E8C8C8Du, 0x3E8E8E8Fu, \
  0x3E909091u, 0x3E929293u, 0x3E949495u, 0x3E969697u, 0x3E989899u, 0x3E9A9A9Bu, 0x3E9C9C9Du, 0x3E9E9E9Fu, \
  0x3EA0A0A1u, 0x3EA2A2A3u, 0x3EA4A4A5u, 0x3EA6A6A7u, 0x3EA8A8A9u, 0x3EAAAAABu, 0x3EACACADu, 0x3EAEAEAFu, \
  0x3EB0B0B1u, 0x3EB2B2B3u, 0x3EB4B4B5u, 0x3EB6B6B7u, 0x3EB8B8B9u, 0x3EBABABBu, 0x3EBCBCBDu, 0x3EBEBEBFu, \
  0x3EC0C0C1u, 0x3EC2C2C3u, 0x3EC4C4C5u, 0x3EC6C6C7u, 0x3EC8C8C9u, 0x3ECACACBu, 0x3ECCCCCDu, 0x3ECECECFu, \
  0x3ED0D0D1u, 0x3ED2D2D3u, 0x3ED4D4D5u, 0x3ED6D6D7u, 0x3ED8D8D9u, 0x3EDADADBu, 0x3EDCDCDDu, 0x3EDEDEDFu, \
  0x3EE0E0E1u, 0x3EE2E2E3u, 0x3EE4E4E5u, 0x3EE6E6E7u, 0x3EE8E8E9u, 0x3EEAEAEBu, 0x3EECECEDu, 0x3EEEEEEFu, \
  0x3EF0F0F1u, 0x3EF2F2F3u, 0x3EF4F4F5u, 0x3EF6F6F7u, 0x3EF8F8F9u, 0x3EFAFAFBu, 0x3EFCFCFDu, 0x3EFEFEFFu, \
  0x3F008081u, 0x3F018182u, 0x3F028283u, 0x3F038384u, 0x3F048485u, 0x3F058586u, 0x3F068687u, 0x3F078788u, \
  0x3F088889u, 0x3F09898Au, 0x3F0A8A8Bu, 0x3F0B8B8Cu, 0x3F0C8C8Du, 0x3F0D8D8Eu, 0x3F0E8E8Fu, 0x3F0F8F90u, \
  0x3F109091u, 0x3F119192u, 0x3F129293u, 0x3F139394u, 0x3F149495u, 0x3F159596u, 0x3F169697u, 0x3F179798u, \
  0x3F189899u, 0x3F19999Au, 0x3F1A9A9Bu, 0x3F1B9B9Cu, 0x3F1C9C9Du, 0x3F1D9D9Eu, 0x3F1E9E9Fu, 0x3F1F9FA0u, \
  0x3F20A0A1u, 0x3F21A1A2u, 0x3F22A2A3u, 0x3F23A3A4u, 0x3F24A4A5u, 0x3F25A5A6u, 0x3F26A6A7u, 0x3F27A7A8u, \
  0x3F28A8A9u, 0x3F29A9AAu, 0x3F2AAAABu, 0x3F2BABACu, 0x3F2CACADu, 0x3F2DADAEu, 0x3F2EAEAFu, 0x3F2FAFB0u, \
  0x3F30B0B1u, 0x3F31B1B2u, 0x3F32B2B3u, 0x3F33B3B4u, 0x3F34B4B5u, 0x3F35B5B6u, 0x3F36B6B7u, 0x3F37B7B8u, \
  0x3F38B8B9u, 0x3F39B9BAu, 0x3F3ABABBu, 0x3F3BBBBCu, 0x3F3CBCBDu, 0x3F3DBDBEu, 0x3F3EBEBFu, 0x3F3FBFC0u, \
  0x3F40C0C1u, 0x3F41C1C2u, 0x3F42C2C3u, 0x3F43C3C4u, 0x3F44C4C5u, 0x3F45C5C6u, 0x3F46C6C7u, 0x3F47C7C8u, \
  0x3F48C8C9u, 0x3F49C9CAu, 0x3F4ACACBu, 0x3F4BCBCCu, 0x3F4CCCCDu, 0x3F4DCDCEu, 0x3F4ECECFu, 0x3F4FCFD0u, \
  0x3F50D0D1u, 0x3F51D1D2u, 0x3F52D2D3u, 0x3F53D3D4u, 0x3F54D4D5u, 0x3F55D5D6u, 0x3F56D6D7u, 0x3F57D7D8u, \
  0x3F58D8D9u, 0x3F59D9DAu, 0x3F5ADADBu, 0x3F5BDBDCu, 0x3F5CDCDDu, 0x3F5DDDDEu, 0x3F5EDEDFu, 0x3F5FDFE0u, \
  0x3F60E0E1u, 0x3F61E1E2u, 0x3F62E2E3u, 0x3F63E3E4u, 0x3F64E4E5u, 0x3F65E5E6u, 0x3F66E6E7u, 0x3F67E7E8u, \
  0x3F68E8E9u, 0x3F69E9EAu, 0x3F6AEAEBu, 0x3F6BEBECu, 0x3F6CECEDu, 0x3F6DEDEEu, 0x3F6EEEEFu, 0x3F6FEFF0u, \
  0x3F70F0F1u, 0x3F71F1F2u, 0x3F72F2F3u, 0x3F73F3F4u, 0x3F74F4F5u, 0x3F75F5F6u, 0x3F76F6F7u, 0x3F77F7F8u, \
  0x3F78F8F9u, 0x3F79F9FAu, 0x3F7AFAFBu, 0x3F7BFBFCu, 0x3F7CFCFDu, 0x3F7DFDFEu, 0x3F7EFEFFu, 0x3F800000u

// The bits of 1.0f / 255.0f: linear 8-bit colour channels are float(c) * (1.0f / 255.0f).
#define SCENE_INV_255_BITS 0x3B808081u

#ifdef __cplusplus
inline constexpr uint32_t scene_srgb_decode_bits[256] = {SCENE_SRGB_DECODE_BITS};
inline constexpr uint32_t scene_unorm8_bits[256] = {SCENE_UNORM8_BITS};
// Both tables as they start scene_texels[]: what TEXTURE_TABLE_WORD reads on the CPU.
inline constexpr uint32_t scene_texel_tables[SCENE_TEXELS_FIRST_TEXEL] = {SCENE_SRGB_DECODE_BITS, SCENE_UNORM8_BITS};
static_assert(SCENE_TEXELS_SRGB_TABLE == 0 && SCENE_TEXELS_UNORM8_TABLE == 256 && SCENE_TEXELS_FIRST_TEXEL == 512);

static_assert(sizeof(SceneVertex) == 64);
static_assert(offsetof(SceneVertex, position) == 0);
static_assert(offsetof(SceneVertex, u) == 12);
static_assert(offsetof(SceneVertex, normal) == 16);
static_assert(offsetof(SceneVertex, v) == 28);
static_assert(offsetof(SceneVertex, tangent) == 32);
static_assert(offsetof(SceneVertex, color) == 48);
static_assert(sizeof(SceneTriangle) == 16);
static_assert(offsetof(SceneTriangle, v0) == 0);
static_assert(offsetof(SceneTriangle, v1) == 4);
static_assert(offsetof(SceneTriangle, v2) == 8);
static_assert(offsetof(SceneTriangle, material) == 12);
static_assert(sizeof(SceneMaterial) == 64);
static_assert(offsetof(SceneMaterial, base_color) == 0);
static_assert(offsetof(SceneMaterial, metallic) == 12);
static_assert(offsetof(SceneMaterial, emission) == 16);
static_assert(offsetof(SceneMaterial, roughness) == 28);
static_assert(offsetof(SceneMaterial, base_color_texture) == 32);
static_assert(offsetof(SceneMaterial, metallic_roughness_texture) == 36);
static_assert(offsetof(SceneMaterial, emissive_texture) == 40);
static_assert(offsetof(SceneMaterial, double_sided) == 44);
static_assert(offsetof(SceneMaterial, alpha) == 48);
static_assert(offsetof(SceneMaterial, alpha_cutoff) == 52);
static_assert(offsetof(SceneMaterial, normal_texture) == 56);
static_assert(offsetof(SceneMaterial, normal_scale) == 60);
static_assert(sizeof(SceneTexture) == 32);
static_assert(offsetof(SceneTexture, texel_offset) == 0);
static_assert(offsetof(SceneTexture, width) == 4);
static_assert(offsetof(SceneTexture, height) == 8);
static_assert(offsetof(SceneTexture, format) == 12);
static_assert(offsetof(SceneTexture, wrap_s) == 16);
static_assert(offsetof(SceneTexture, wrap_t) == 20);
static_assert(offsetof(SceneTexture, nearest) == 24);
static_assert(offsetof(SceneTexture, reserved) == 28);
}  // namespace sst::glsl

namespace sst {
using glsl::SceneMaterial;
using glsl::SceneTexture;
using glsl::SceneTriangle;
using glsl::SceneVertex;
}  // namespace sst
#else
// Declares the five scene buffers, read-only, at bindings first .. first + 4 in the order of the
// list at the top (vertices, triangles, materials, textures, texels): the order of
// sst::gpu::GpuScene::buffers().
#define SCENE_BUFFERS(first)                                                                        \
  layout(std430, binding = (first)) readonly buffer SceneVertices { SceneVertex scene_vertices[]; };  \
  layout(std430, binding = (first) + 1) readonly buffer SceneTriangles { SceneTriangle scene_triangles[]; }; \
  layout(std430, binding = (first) + 2) readonly buffer SceneMaterials { SceneMaterial scene_materials[]; }; \
  layout(std430, binding = (first) + 3) readonly buffer SceneTextures { SceneTexture scene_textures[]; };   \
  layout(std430, binding = (first) + 4) readonly buffer SceneTexels { uint scene_texels[]; };
#endif

#endif  // SST_CORE_SCENE_SCENE_LAYOUT_H
