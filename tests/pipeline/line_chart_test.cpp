// Line charts (pipeline/line_chart.h): the ticks matplotlib's MaxNLocator picks, their labels,
// and values placed on a linear axis: lines at 0, 1 and 2 J drawn equally far apart, in their
// series' colours, the larger value higher.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "pipeline/line_chart.h"

namespace shatter {
namespace {

TEST(LineChart, TicksAreTheLeastStepOf1_2_25_5TimesAPowerOfTenWithinTheIntervals) {
    // The demo's energy plot: -17.8 to 17.3 J with 5% margins, 9 intervals at most: steps of 5.
    EXPECT_EQ(nice_ticks(-19.6, 19.5, 9), (std::vector<double>{-15, -10, -5, 0, 5, 10, 15}));
    // Its time axis, 0 to 2.07 s with margins: 2.28 / 9 = 0.253 is over 0.25, so steps of 0.5.
    EXPECT_EQ(nice_ticks(-0.1035, 2.1735, 9), (std::vector<double>{0, 0.5, 1, 1.5, 2}));
    const std::vector<double> tenths = nice_ticks(0, 1, 9);  // 1 / 9 = 0.111: steps of 0.2, ends included
    ASSERT_EQ(tenths.size(), 6u);
    for (size_t i = 0; i < tenths.size(); ++i) EXPECT_NEAR(tenths[i], 0.2 * double(i), 1e-12);
    const std::vector<double> quarters = nice_ticks(0.01, 0.99, 4);  // 0.245: steps of 0.25
    EXPECT_EQ(quarters, (std::vector<double>{0.25, 0.5, 0.75}));
    EXPECT_TRUE(nice_ticks(1, 1, 9).empty());
    EXPECT_TRUE(nice_ticks(0, NAN, 9).empty());
}

TEST(LineChart, TickLabelsHaveTheStepsDecimalsAndATrueMinus) {
    EXPECT_EQ(tick_label(-15, 5), "\u221215");
    EXPECT_EQ(tick_label(1, 0.5), "1.0");
    EXPECT_EQ(tick_label(0.75, 0.25), "0.75");
    EXPECT_EQ(tick_label(-1e-17, 0.5), "0.0");  // no "-0.0" from rounding
    EXPECT_EQ(tick_label(2e-5, 1e-5), "0.00002");
}

// The rows (from the top) of column x whose colour is within 40 levels of c.
std::vector<int> rows_of(const Image& img, uint32_t x, Rgb c) {
    std::vector<int> rows;
    for (uint32_t y = 0; y < img.height; ++y) {
        const uint8_t* p = img.pixel(x, y);
        if (std::abs(p[0] - c.r) + std::abs(p[1] - c.g) + std::abs(p[2] - c.b) < 40) rows.push_back(int(y));
    }
    return rows;
}

std::optional<double> middle(const std::vector<int>& rows) {
    if (rows.empty()) return std::nullopt;
    return 0.5 * (rows.front() + rows.back());
}

TEST(LineChart, ValuesLieOnALinearAxis) {
    LineChart chart;
    chart.title = "levels";
    chart.x_label = "time (s)";
    chart.y_label = "energy (J)";
    const std::vector<double> t{0, 1, 2};
    for (int level = 0; level < 3; ++level) {
        ChartSeries s;
        s.x = t;
        s.y.assign(3, double(level));
        s.colour = tab10(size_t(level));
        s.label = "level " + std::to_string(level);
        chart.series.push_back(s);
    }
    const Image img = draw_chart(chart);
    ASSERT_EQ(img.width, 800u);
    ASSERT_EQ(img.height, 450u);
    // A column inside the axes away from the legend (which takes one corner): both sides tried.
    bool checked = false;
    for (uint32_t x : {200u, 600u}) {
        const auto y0 = middle(rows_of(img, x, tab10(0))), y1 = middle(rows_of(img, x, tab10(1))),
                   y2 = middle(rows_of(img, x, tab10(2)));
        if (!y0 || !y1 || !y2) continue;
        checked = true;
        EXPECT_GT(*y0, *y1);  // 0 J below 1 J below 2 J
        EXPECT_GT(*y1, *y2);
        EXPECT_NEAR(*y0 - *y1, *y1 - *y2, 1.0) << "at x = " << x;
        // The three levels span 90% of the axes' height (5% margins), 2 / 2.2 of the range.
        EXPECT_GT(*y0 - *y2, 250);
    }
    EXPECT_TRUE(checked) << "no column showed all three lines";
    EXPECT_EQ(draw_chart(chart).rgb, img.rgb);  // the same pixels again
}

// Whatever the numbers, a chart of the fixed size: one value, equal values, values too large for
// a range (left out), none at all. A constant line sits halfway up its axes (its 5% margins).
TEST(LineChart, DegenerateDataStillDraws) {
    for (const std::vector<double>& ys : std::vector<std::vector<double>>{
             {1e300, -1e300}, {5, 5}, {0, 0}, {1e-300, 2e-300}, {1e30, 1e30 * (1 + 1e-9)}, {-3, INFINITY}}) {
        LineChart c;
        ChartSeries s;
        s.x = {0, 1};
        s.y = ys;
        s.colour = tab10(0);
        c.series.push_back(s);
        const Image img = draw_chart(c);
        EXPECT_EQ(img.width, 800u);
        EXPECT_EQ(img.height, 450u);
    }
    LineChart flat;
    ChartSeries s;
    s.x = {0, 1, 2};
    s.y = {5, 5, 5};
    s.colour = tab10(0);
    flat.series.push_back(s);
    const Image img = draw_chart(flat);
    const auto rows = rows_of(img, 400, tab10(0));
    ASSERT_FALSE(rows.empty());
    // The axes' frame: the first dark rows in column 400 above and below the line (its spines).
    const int line = int(*middle(rows));
    const auto dark = [&](int y) {
        const uint8_t* p = img.pixel(400, uint32_t(y));
        return p[0] < 160 && p[1] < 160 && p[2] < 160;
    };
    int top = line - 3, bottom = line + 3;
    while (top > 0 && !dark(top)) --top;
    while (bottom + 1 < int(img.height) && !dark(bottom)) ++bottom;
    EXPECT_NEAR(line, 0.5 * (top + bottom), 2.0) << "spines at rows " << top << " and " << bottom;
    LineChart none;
    EXPECT_EQ(draw_chart(none).width, 800u);
}

}  // namespace
}  // namespace shatter
