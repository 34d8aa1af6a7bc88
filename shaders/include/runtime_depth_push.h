// Push constants of shaders/runtime/depth_only.vert (shadow maps and the occluder pass), for GLSL and C++.
#ifndef GUSUKU_RUNTIME_DEPTH_PUSH_H
#define GUSUKU_RUNTIME_DEPTH_PUSH_H
#include "interface_types.h"
GUSUKU_PUSH_CONSTANTS_BEGIN(DepthOnlyPushConstants)
    mat4 enu_to_clip;  // the view this depth pass renders (the sun's or the camera's)
    vec3 pull_origin;  // ENU metres: the point vertices are moved towards
    float pull_m;      // metres to move each vertex towards `pull_origin` (0: none; < 0 moves it away)
    float drop_m;      // metres to move each vertex down first (the occluder: its simplification error; else 0)
GUSUKU_PUSH_CONSTANTS_END(DepthOnlyPushConstants, push)
#endif
