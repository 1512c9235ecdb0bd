// VPLs as a point cloud for inspection (MeshLab, CloudCompare, Blender): binary little-endian
// PLY, one vertex per VPL with float x y z, nx ny nz, r g b (intensity, W/sr per channel, the
// exact values) and uchar red green blue (a display colour: intensity tone-mapped against the
// set's mean luminance, so a viewer shows where the light went).
#pragma once
#include <string>

#include "core/vpl/vpl.h"

namespace sst {

// Written atomically (temp file + rename); parent folders are created.
void write_vpls_ply(const std::string& path, const VplSet& vpls);
// Reads a binary little-endian PLY with at least the float properties above (any order, extra
// properties skipped). Throws sst::Error naming the file for anything else.
VplSet read_vpls_ply(const std::string& path);

}  // namespace sst
