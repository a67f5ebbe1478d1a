// What the scene layer is told by a render: which camera and lens, the resolution and the path
// length. The rest of a render's settings (integrators/render_settings.h) do not concern it.
#pragma once

namespace clppm {

struct SceneSettings {
    unsigned width = 0, height = 0; // 0: from the camera (height 512, width by aspect)
    unsigned camera = 0;
    unsigned max_bounces = 16;
    double aperture = -1;      // thin-lens radius; < 0: the camera's own (0: pinhole)
    double focus_distance = 0; // 0: the camera's own, else the distance to the scene centre
};

} // namespace clppm
