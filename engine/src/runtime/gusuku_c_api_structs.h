#pragma once
// The C API's options, frame and result structs (gusuku.h) to and from the C++ runtime's (runtime.h): today's
// defaults, and field-by-field conversions. Not a public header: not installed.

#include <string>

#include "gusuku/runtime/gusuku.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::c_api_detail {

/// Today's defaults as full structs (struct_size = this library's sizeof), from RuntimeOptions' and FrameInput's.
gusuku_runtime_options defaultOptions();
gusuku_frame_input defaultFrame();

RuntimeOptions convertOptions(const gusuku_runtime_options& options);
CameraIntrinsics convertIntrinsics(const gusuku_intrinsics& intrinsics);
CameraPose convertPose(const gusuku_pose& pose);
gusuku_pose convertPose(const CameraPose& pose);

/// The C frame as the C++ one; "" or the problem with an enum or flag the C++ side cannot represent.
std::string convertFrame(const gusuku_frame_input& frame, FrameInput& converted);

gusuku_frame_info convertInfo(const FrameInfo& info);
gusuku_pass_timings convertTimings(const PassTimings& timings);

}  // namespace gusuku::c_api_detail
