#version 450
// Depth only: the building and the site's occluder mesh into the sun's shadow maps, and the occluder mesh into
// the camera's depth (so real walls hide the building; docs/design.md 8 steps 3 and 4). Positions in ENU metres.
#extension GL_GOOGLE_include_directive : require
#include "runtime_depth_push.h"

layout(location = 0) in vec3 position_enu;

void main() {
    vec3 position = position_enu;
    // The occluder lies within its simplification error of the SfM mesh, above it as often as below: lowered by
    // that error, its ground no longer hides the foot of a building standing on the real ground (a 2 cm platform's
    // side face, drawn as the ground's camera pixel: 0.75 of the truth; docs/design.md 3).
    position.z -= push.drop_m;
    // The occluder is pushed a little away from the camera (pull_m < 0) so the ground it was built from does not
    // hide the ground-ratio pass drawn on the same surface.
    if (push.pull_m != 0.0) position += normalize(push.pull_origin - position) * push.pull_m;
    gl_Position = push.enu_to_clip * vec4(position, 1.0);
}
