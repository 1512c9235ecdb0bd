# cmake -DOUT=file.cpp -DFILES="a.spv|b.spv" -P embed_spirv.cmake
# Writes a C++ source defining sst::gpu::embedded_spirv(name) for each SPIR-V file's words, at
# build time (the .spv files are build outputs of glslc, so configure-time embedding cannot see them).
string(REPLACE "|" ";" files "${FILES}")
set(body "#include <cstdint>\n#include <span>\n#include <string_view>\nnamespace sst::gpu {\nnamespace {\n")
set(table "")
set(i 0)
foreach(f ${files})
  file(READ ${f} hex HEX)
  # Little-endian 32-bit words: bytes b0 b1 b2 b3 -> 0xb3b2b1b0.
  string(REGEX REPLACE "([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])" "0x\\4\\3\\2\\1u," words "${hex}")
  get_filename_component(name ${f} NAME_WE)
  string(APPEND body "const uint32_t spirv_${i}[] = {${words}};\n")
  string(APPEND table "  if (name == \"${name}\") return spirv_${i};\n")
  math(EXPR i "${i}+1")
endforeach()
string(APPEND body "}  // namespace\n// Empty when no shader of that name was compiled in.\nstd::span<const uint32_t> embedded_spirv(std::string_view name) {\n${table}  return {};\n}\n}  // namespace sst::gpu\n")
file(WRITE ${OUT}.tmp "${body}")
configure_file(${OUT}.tmp ${OUT} COPYONLY)
