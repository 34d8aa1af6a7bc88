#pragma once
// What the viewer shows, and how input changes it: the camera (a centre and the point it looks at, which the
// mouse orbits about and walks with), the instant on the bake date, the cloud cover, the mode and multisampling.
// The same changes come from the keyboard and mouse, and from scripted actions (view_script.h).

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

namespace gusuku::view {

struct ViewState {
    glm::dvec3 position_enu{0.0, -25.0, 6.0};
    glm::dvec3 look_at_enu{0.0, 0.0, 2.0};
    double horizontal_fov_deg = 60.0;
    double utc_seconds = 0.0;
    float cloud_cover = 0.0f;
    size_t mode_index = 0;        ///< into kViewModeNames (view_modes.h)
    uint32_t msaa_samples = 4;
    std::string weather_source = "command line";  ///< who set cloud_cover last: command line, keys, script
    bool overlay = true;  ///< the text box over the image's top-left (O toggles it; view_overlay.h)

    /// Turns the camera about the vertical axis through the point looked at, by `degrees` (counter-clockwise
    /// seen from above): position' = look_at + Rz(degrees) (position - look_at).
    void orbit(double degrees);
    /// Raises the camera about the point looked at by `degrees` of elevation, the distance kept; held within 85
    /// degrees of the horizon.
    void pitch(double degrees);
    /// Moves camera and point looked at together by `metres` along the horizontal direction the camera faces.
    void walk(double metres);
    /// Moves both sideways (positive: to the right), `metres`.
    void strafe(double metres);
    /// Moves the camera towards the point looked at by `fraction` of the distance (negative: away), staying at
    /// least 0.5 m from it.
    void dolly(double fraction);
};

}  // namespace gusuku::view
