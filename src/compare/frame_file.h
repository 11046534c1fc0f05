// A frame kept whole for a later process (a study's references, study/run.h): every field the
// measures of compare/measure.h read (colour, its variance, each light's visibility, per-sample
// transmittance, unshadowed mask and variance, the G-buffer, memory and statistics; not the
// timings), as raw little-endian floats, so that errors measured against a frame read back are
// bit-identical to errors measured against it in memory. Not an exchange format: a job's id
// includes the build, so a file is only ever read by the build that wrote it.
#pragma once

#include <string>

#include "pipeline/renderer.h"

namespace penumbra {

// Written whole or not at all (core/files.h writeAtomically).
void writeFrameFile(const std::string& path, const FrameResult& frame);
// A file that is not such a frame, or is cut short: penumbra::Error naming it.
FrameResult readFrameFile(const std::string& path);

}  // namespace penumbra
