#include "scene/light_power.h"

namespace clppm {

namespace {

constexpr double kPi = 3.14159265358979323846;

} // namespace

double punctual_light_power(const dev::Light& l, double scene_radius) {
    const double i = (double(l.radiance[0]) + l.radiance[1] + l.radiance[2]) / 3.0;
    switch (l.type) {
    case LIGHT_POINT: return 4 * kPi * i;
    case LIGHT_SPOT: return 2 * kPi * i * ((1 - double(l.cos_inner)) + (double(l.cos_inner) - l.cos_outer) / 3);
    case LIGHT_DIRECTIONAL: return i * kPi * scene_radius * scene_radius;
    default: return 0;
    }
}

} // namespace clppm
