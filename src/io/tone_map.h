// How the 8-bit PNG preview shows linear radiance: an exposure in stops, optionally chosen from
// the image, then a tone curve per channel, then the sRGB OETF (image_io.h). The EXR is never
// touched: it stays linear, and records in its header what the PNG beside it applied.
#pragma once
#include <string>

#include "util/enum_names.h"

namespace clppm {

struct Image;

enum class ToneCurve {
    Clip,     // min(x, 1): the radiance as it is, up to white
    Aces,     // Narkowicz's 2015 fit of the ACES filmic curve
    Reinhard, // x / (1 + x) (Reinhard et al. 2002, Eq. 3)
};

struct ToneMapping {
    ToneCurve curve = ToneCurve::Clip;
    double exposure_ev = 0.0;   // stops: linear values are scaled by 2^EV before the curve
    bool auto_exposure = false; // add auto_exposure_ev(image) to exposure_ev
};

// The curve at exposed linear value x, in [0, 1]; monotone non-decreasing in x, 0 at 0 (NaN and
// negative values give 0).
double tone_curve(ToneCurve curve, double x);

// The exposure that maps the image's log-average luminance to middle grey 0.18 (Reinhard et al.
// 2002, Eq. 1 and 2: the key 0.18 over exp(mean log L)), in stops, within [-64, 64]; the mean is
// over the pixels that show something (finite L > 0), so a black background does not blow the
// object out; 0 for an image without such a pixel.
double auto_exposure_ev(const Image& img);

// The stops applied to `img`: exposure_ev, plus auto_exposure_ev(img) when asked.
double applied_exposure_ev(const ToneMapping& tm, const Image& img);

// "clip", "aces", "reinhard", and back (case-insensitively); false for any other name.
constexpr EnumName<ToneCurve> kToneCurveNames[] = {
    {ToneCurve::Clip, "clip"}, {ToneCurve::Aces, "aces"}, {ToneCurve::Reinhard, "reinhard"}};
constexpr const auto& enum_names(ToneCurve) { return kToneCurveNames; }

} // namespace clppm
