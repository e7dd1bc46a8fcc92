// Line charts drawn to an image in-process: the energy plots of a run and of a sweep. The look
// follows matplotlib's defaults (its tab10 colours, DejaVu Sans, 8 x 4.5 inches at 100 dpi,
// ticks at 1, 2, 2.5 or 5 times a power of ten, a grid, the legend where it covers the fewest
// points), so the figures read as the ones people know. Text is drawn by stb_truetype from
// Debian's DejaVu Sans (fonts-dejavu-core); without that file, by the built-in 5x7 font
// (pipeline/font.h). Lines are anti-aliased by their distance to each pixel's centre; a series'
// segments share one coverage, so its joints are not darker. The same chart gives the same pixels.
#pragma once

#include <string>
#include <vector>

#include "pipeline/font.h"
#include "render/image.h"

namespace shatter {

enum class Dash { Solid, Dashed, Dotted, DashDot };

struct ChartSeries {
    std::vector<double> x, y;  // the same length; a series without points is a legend entry alone
    Rgb colour;
    Dash dash = Dash::Solid;
    double width = 1.5;  // (unit: points, 1/72 inch)
    std::string label;   // UTF-8; empty: not in the legend
};

struct LineChart {
    std::string title, x_label, y_label;  // UTF-8
    std::string legend_title;             // empty: none
    bool small_legend = true;             // the legend's text at 8.3 points, else 10
    std::vector<ChartSeries> series;      // drawn in order, the last on top
};

// matplotlib's tab10 cycle: colour `i` of "C0" to "C9".
Rgb tab10(size_t i);

// The ticks of an axis over [lo, hi]: the multiples of the least step of 1, 2, 2.5, 5 or 10 times a
// power of ten that makes at most `intervals` intervals of the range (matplotlib's MaxNLocator),
// those within [lo, hi]. Empty when the range is empty or not finite.
std::vector<double> nice_ticks(double lo, double hi, int intervals);

// A tick's label: as many decimals as the step needs, a minus sign (U+2212) for negatives.
std::string tick_label(double value, double step);

// The chart at width x height pixels (100 dpi).
Image draw_chart(const LineChart& chart, uint32_t width = 800, uint32_t height = 450);

}  // namespace shatter
