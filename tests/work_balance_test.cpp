// The split of a pass between processes (integrators/work_balance.h): the fit of t = a + b c, and
// the shares that make a + b c equal, against hand-worked cases.
#include <gtest/gtest.h>

#include <numeric>

#include "integrators/work_balance.h"

using namespace clppm;

TEST(WorkBalance, TheFitFindsTheFixedAndThePerUnitCost) {
    WorkBalance w;
    EXPECT_EQ(w.model(), std::make_pair(0.0, 0.0));
    for (double c : {1000.0, 2000.0, 4000.0, 3000.0}) w.record(c, 0.5 + 1e-4 * c);
    const auto [a, b] = w.model();
    EXPECT_NEAR(a, 0.5, 1e-9);
    EXPECT_NEAR(b, 1e-4, 1e-12);
}

TEST(WorkBalance, EqualSharesGiveTheMeanRateOnly) {
    WorkBalance w;
    for (int i = 0; i < 5; ++i) w.record(1000, 0.2);
    const auto [a, b] = w.model();
    EXPECT_EQ(a, 0.0);
    EXPECT_DOUBLE_EQ(b, 0.2 / 1000);
}

TEST(WorkBalance, SharesEqualiseTheTimes) {
    // Twice as fast per unit, same fixed part: T = (3000 + 0.1/1e-4 + 0.1/2e-4) / (1/1e-4 + 1/2e-4)
    // = 4500 / 15000 = 0.3 s; shares (0.3 - 0.1) / 1e-4 = 2000 and 1000.
    const auto c = WorkBalance::split(3000, {0.1, 0.1}, {1e-4, 2e-4});
    EXPECT_EQ(c, (std::vector<uint32_t>{2000, 1000}));
    // Unknown speeds: equal shares, the first taking the rounding.
    EXPECT_EQ(WorkBalance::split(10, {0, 0, 0}, {0, 0, 0}), (std::vector<uint32_t>{4, 3, 3}));
    // A process whose fixed part alone is longer than the others' whole pass gets only its floor,
    // a tenth of an equal share, and goes on being measured.
    const auto d = WorkBalance::split(1000, {0.0, 5.0}, {1e-4, 1e-4});
    EXPECT_EQ(d, (std::vector<uint32_t>{950, 50}));
    // Always the total, whatever the inputs.
    const auto e = WorkBalance::split(12345, {0.01, 0.2, 0.0, 0.05}, {3e-5, 1e-5, 7e-5, 2e-5});
    EXPECT_EQ(std::accumulate(e.begin(), e.end(), 0u), 12345u);
}
