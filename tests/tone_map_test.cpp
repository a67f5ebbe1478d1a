// The PNG's tone mapping (io/tone_map.h): the curves are monotone, bounded and exact where they
// have closed values; automatic exposure puts the log-average at middle grey; a PNG written with an
// exposure shows exactly the scaled value.
#include "io/tone_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/image_io.h"
#include "test_util.h"

namespace clppm {
namespace {

const ToneCurve kCurves[] = {ToneCurve::Clip, ToneCurve::Aces, ToneCurve::Reinhard};

TEST(ToneMap, CurvesAreMonotoneBoundedAndZeroAtZero) {
    for (ToneCurve c : kCurves) {
        SCOPED_TRACE(to_string(c));
        EXPECT_EQ(tone_curve(c, 0), 0);
        EXPECT_EQ(tone_curve(c, -1), 0);
        EXPECT_EQ(tone_curve(c, std::numeric_limits<double>::quiet_NaN()), 0);
        EXPECT_EQ(tone_curve(c, std::numeric_limits<double>::infinity()), 1);
        double last = 0;
        size_t rising = 0;
        // 1e-6 to 1e6 in steps of 0.1%.
        for (double x = 1e-6; x < 1e6; x *= 1.001) {
            const double y = tone_curve(c, x);
            ASSERT_GE(y, last) << x;
            ASSERT_LE(y, 1.0) << x;
            rising += y > last;
            last = y;
        }
        EXPECT_GT(rising, 1000u); // not a step
        EXPECT_GT(last, 0.999);   // white is reached, or nearly
    }
}

TEST(ToneMap, ClosedFormValues) {
    EXPECT_EQ(tone_curve(ToneCurve::Clip, 0.25), 0.25);
    EXPECT_EQ(tone_curve(ToneCurve::Clip, 7.0), 1.0);
    EXPECT_DOUBLE_EQ(tone_curve(ToneCurve::Reinhard, 1.0), 0.5);
    EXPECT_DOUBLE_EQ(tone_curve(ToneCurve::Reinhard, 3.0), 0.75);
    // Narkowicz's fit at 1: 2.54 / 3.16.
    EXPECT_DOUBLE_EQ(tone_curve(ToneCurve::Aces, 1.0), 2.54 / 3.16);
    EXPECT_EQ(tone_curve(ToneCurve::Aces, 100.0), 1.0); // past its crossing of 1: clipped
}

TEST(ToneMap, AutoExposurePutsTheLogAverageAtMiddleGrey) {
    Image img;
    img.width = 2, img.height = 2;
    // Luminances 0.045 * 4 and 0.045 / 4 (grey pixels): log-average 0.045, so +2 stops.
    img.rgb = {0.18f, 0.18f, 0.18f, 0.01125f, 0.01125f, 0.01125f, 0.18f, 0.18f, 0.18f, 0.01125f, 0.01125f, 0.01125f};
    EXPECT_NEAR(auto_exposure_ev(img), 2.0, 1e-6);
    ToneMapping tm{ToneCurve::Clip, -0.5, true};
    EXPECT_NEAR(applied_exposure_ev(tm, img), 1.5, 1e-6);
    tm.auto_exposure = false;
    EXPECT_EQ(applied_exposure_ev(tm, img), -0.5);
    // A black image is left alone; black (a background) and non-finite pixels do not move it.
    Image black = img;
    for (float& v : black.rgb) v = 0;
    EXPECT_EQ(auto_exposure_ev(black), 0);
    Image more = img;
    more.rgb.insert(more.rgb.end(), {NAN, NAN, NAN, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f});
    more.width = 8, more.height = 1;
    EXPECT_NEAR(auto_exposure_ev(more), 2.0, 1e-6);
}

TEST(ToneMap, NamesParseCaseInsensitively) {
    EXPECT_EQ(enum_from_name<ToneCurve>("ACES"), ToneCurve::Aces);
    EXPECT_EQ(enum_from_name<ToneCurve>("Reinhard"), ToneCurve::Reinhard);
    EXPECT_EQ(enum_from_name<ToneCurve>("clip"), ToneCurve::Clip);
    EXPECT_EQ(enum_from_name<ToneCurve>("agx"), std::nullopt);
    EXPECT_STREQ(to_string(ToneCurve::Reinhard), "reinhard");
    EXPECT_EQ(enum_choices<ToneCurve>(), "clip, aces or reinhard");
}

} // namespace
} // namespace clppm
