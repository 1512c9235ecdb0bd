// What a sequence's next frame needs from the frames before it, and its file: saved after a frame,
// it lets an interrupted sequence continue with exactly the frames it would have rendered (every
// frame's random numbers come from its index; the history of temporal reuse, ReSTIR's histories
// and the previous camera and pose are the only state carried between frames).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/math/vector_math.h"
#include "core/render/frame_layout.h"
#include "core/temporal/temporal_layout.h"

namespace sst {

struct SequenceState {
  int next = 0;                         // position in the sequence (0-based) of the next frame to render
  bool has_previous = false;            // whether a frame was rendered before `next`
  glsl::ViewParams view{};              // that frame's camera
  std::vector<vec3> positions;          // the scene's vertices as that frame saw them
  std::vector<TemporalTexel> temporal;  // the history of temporal reuse (empty without it)
  // FrameRenderer::save_histories: ReSTIR DI's history and the method's own (bytes; empty: none).
  std::vector<uint8_t> direct_history, method_history;
};

// Binary, written atomically. read_sequence_state throws sst::Error naming the file when it is
// not a state this build wrote (another version, truncated).
void write_sequence_state(const std::string& path, const SequenceState& state);
SequenceState read_sequence_state(const std::string& path);

}  // namespace sst
