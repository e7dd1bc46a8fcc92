#include "pipeline/line_chart.h"

#include <stb/stb_truetype.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

namespace shatter {

namespace {

constexpr double kDpi = 100;
constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";  // fonts-dejavu-core
constexpr Rgb kBlack{0, 0, 0};

double px(double points) { return points * kDpi / 72; }

// A value the axes can hold: finite, and small enough that a range of two of them is too.
bool drawable(double v) { return std::isfinite(v) && std::abs(v) < 1e150; }

// matplotlib's rcParams, in points: font sizes, the padding of tight_layout, ticks and labels.
constexpr double kFontPt = 10, kTitlePt = 12, kSmallPt = 10 * 0.833;
constexpr double kLayoutPad = 1.08 * kFontPt, kTickLength = 3.5, kTickPad = 3.5, kLabelPad = 4, kTitlePad = 6;
constexpr double kAxisWidth = 0.8;  // spines, ticks and the grid
constexpr double kMargin = 0.05;    // of the data range, on each side

struct TrueType {
    std::string data;
    stbtt_fontinfo info{};
    bool ok = false;
};

// DejaVu Sans, read once (thread-safe: a function-local static).
const TrueType& dejavu() {
    static const TrueType font = [] {
        TrueType f;
        std::ifstream in(kFontPath, std::ios::binary);
        if (!in) return f;
        f.data.assign(std::istreambuf_iterator<char>(in), {});
        const auto* bytes = reinterpret_cast<const unsigned char*>(f.data.data());
        const int offset = stbtt_GetFontOffsetForIndex(bytes, 0);
        f.ok = offset >= 0 && stbtt_InitFont(&f.info, bytes, offset) != 0;
        return f;
    }();
    return font;
}

// A grey-level image: a line of text, or a series' lines, before they are laid on the chart; the
// box its lines touched (x0..x1, y0..y1; empty when x1 < x0), so that laying it walks that alone.
struct Coverage {
    int width = 0, height = 0;
    std::vector<float> a;
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    Coverage(int w, int h) : width(std::max(w, 0)), height(std::max(h, 0)), a(size_t(width) * size_t(height), 0.f) {}
    float& at(int x, int y) { return a[size_t(y) * size_t(width) + size_t(x)]; }
    float at(int x, int y) const { return a[size_t(y) * size_t(width) + size_t(x)]; }
    void touch(int left, int top, int right, int bottom) {
        if (right < left || bottom < top) return;
        if (x1 < x0) x0 = left, y0 = top, x1 = right, y1 = bottom;
        x0 = std::min(x0, left), y0 = std::min(y0, top), x1 = std::max(x1, right), y1 = std::max(y1, bottom);
    }
};

void blend(Image& image, int x, int y, Rgb c, double alpha) {
    if (x < 0 || y < 0 || x >= int(image.width) || y >= int(image.height) || !(alpha > 0)) return;
    alpha = std::min(alpha, 1.0);
    uint8_t* p = image.pixel(uint32_t(x), uint32_t(y));
    const std::array<uint8_t, 3> to{c.r, c.g, c.b};
    for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::lround(p[k] + (to[size_t(k)] - p[k]) * alpha));
}

// Text at one size: measured and drawn with the baseline's left end at a point.
class Text {
public:
    explicit Text(double points) : size_(px(points)) {
        const TrueType& f = dejavu();
        if (!f.ok) {
            fallback_ = std::max(1, int(std::lround(size_ / 8)));  // the 5x7 font's 7 rows about a cap height
            return;
        }
        scale_ = stbtt_ScaleForMappingEmToPixels(&f.info, float(size_));
        int ascent = 0, descent = 0, gap = 0;
        stbtt_GetFontVMetrics(&f.info, &ascent, &descent, &gap);
        ascent_ = ascent * scale_, descent_ = -descent * scale_;
    }
    double ascent() const { return fallback_ ? kGlyphHeight * fallback_ : ascent_; }
    double descent() const { return fallback_ ? 0.0 : descent_; }
    double height() const { return ascent() + descent(); }
    double width(std::string_view s) const {
        if (fallback_) return text_width(plain(s), fallback_);
        double w = 0;
        for (size_t i = 0; i < s.size();) {
            const char32_t c = next_code_point(s, i);
            w += advance(c, s, i);
        }
        return w;
    }
    // The text's grey levels: width(s) wide (rounded up), height() tall, the baseline at ascent().
    Coverage render(std::string_view s) const {
        Coverage out(int(std::ceil(width(s))) + 2, int(std::ceil(height())) + 2);
        if (fallback_) {
            Image ink(uint32_t(out.width), uint32_t(out.height));
            draw_text(ink, 0, 0, plain(s), fallback_, Rgb{255, 255, 255});
            for (int y = 0; y < out.height; ++y)
                for (int x = 0; x < out.width; ++x) out.at(x, y) = ink.pixel(uint32_t(x), uint32_t(y))[0] / 255.f;
            return out;
        }
        const TrueType& f = dejavu();
        const int baseline = int(std::lround(ascent_));
        double pen = 0;
        std::vector<unsigned char> glyph;
        for (size_t i = 0; i < s.size();) {
            const char32_t c = next_code_point(s, i);
            const double x = std::floor(pen);
            const float shift = float(pen - x);
            int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
            stbtt_GetCodepointBitmapBoxSubpixel(&f.info, int(c), scale_, scale_, shift, 0, &x0, &y0, &x1, &y1);
            const int w = x1 - x0, h = y1 - y0;
            if (w > 0 && h > 0) {
                glyph.assign(size_t(w) * size_t(h), 0);
                stbtt_MakeCodepointBitmapSubpixel(&f.info, glyph.data(), w, h, w, scale_, scale_, shift, 0, int(c));
                for (int gy = 0; gy < h; ++gy)
                    for (int gx = 0; gx < w; ++gx) {
                        const int ox = int(x) + x0 + gx, oy = baseline + y0 + gy;
                        if (ox < 0 || oy < 0 || ox >= out.width || oy >= out.height) continue;
                        out.at(ox, oy) = std::min(1.f, out.at(ox, oy) + glyph[size_t(gy) * size_t(w) + size_t(gx)] / 255.f);
                    }
            }
            pen += advance(c, s, i);
        }
        return out;
    }
    // Drawn with the baseline's left end at (x, baseline).
    void draw(Image& image, double x, double baseline, std::string_view s, Rgb colour) const {
        const Coverage ink = render(s);
        const int left = int(std::lround(x)), top = int(std::lround(baseline - ascent()));
        for (int y = 0; y < ink.height; ++y)
            for (int xx = 0; xx < ink.width; ++xx) blend(image, left + xx, top + y, colour, ink.at(xx, y));
    }
    // Turned a quarter to the left (read from the bottom up), its top at x = left, its middle at
    // height `middle`.
    void draw_up(Image& image, double left, double middle, std::string_view s, Rgb colour) const {
        const Coverage ink = render(s);
        const int x0 = int(std::lround(left)), bottom = int(std::lround(middle + width(s) / 2));
        for (int v = 0; v < ink.height; ++v)
            for (int u = 0; u < ink.width; ++u) blend(image, x0 + v, bottom - u, colour, ink.at(u, v));
    }

private:
    // How far the pen moves past code point `c` of DejaVu Sans, the next being the one at byte
    // `next` of `s` (kerning included).
    double advance(char32_t c, std::string_view s, size_t next) const {
        const TrueType& f = dejavu();
        int width = 0, lsb = 0;
        stbtt_GetCodepointHMetrics(&f.info, int(c), &width, &lsb);
        double pen = width * scale_;
        if (next < s.size()) pen += scale_ * stbtt_GetCodepointKernAdvance(&f.info, int(c), int(next_code_point(s, next)));
        return pen;
    }
    // For the built-in font, which has no minus sign (U+2212): a hyphen.
    static std::string plain(std::string_view s) {
        constexpr std::string_view minus = "\u2212";
        std::string out;
        for (size_t i = 0; i < s.size();) {
            if (s.substr(i, minus.size()) == minus) out += '-', i += minus.size();
            else out += s[i++];
        }
        return out;
    }
    double size_;
    float scale_ = 1;
    double ascent_ = 0, descent_ = 0;
    int fallback_ = 0;  // the built-in font's scale, when DejaVu Sans is not there
};

struct Point {
    double x, y;
};

struct Box {
    double left, top, right, bottom;
    bool contains(Point p) const { return p.x >= left && p.x <= right && p.y >= top && p.y <= bottom; }
};

// A segment's anti-aliased coverage (the distance of each pixel's centre to it; `butt`: cut square
// at its ends, else rounded), the most of it and what is there kept, within `clip`.
void segment(Coverage& c, Point p, Point q, double half_width, bool butt, const Box& clip) {
    const double dx = q.x - p.x, dy = q.y - p.y, length = std::hypot(dx, dy);
    const double reach = half_width + 1;
    const int x0 = std::max(int(std::floor(std::max(std::min(p.x, q.x) - reach, clip.left))), 0);
    const int x1 = std::min(int(std::ceil(std::min(std::max(p.x, q.x) + reach, clip.right))), c.width - 1);
    const int y0 = std::max(int(std::floor(std::max(std::min(p.y, q.y) - reach, clip.top))), 0);
    const int y1 = std::min(int(std::ceil(std::min(std::max(p.y, q.y) + reach, clip.bottom))), c.height - 1);
    c.touch(x0, y0, x1, y1);
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const double cx = x + 0.5 - p.x, cy = y + 0.5 - p.y;
            double cover;
            if (length < 1e-12) {
                cover = butt ? 0 : std::clamp(half_width + 0.5 - std::hypot(cx, cy), 0.0, 1.0);
            } else {
                const double along = (cx * dx + cy * dy) / length, across = std::abs(cx * dy - cy * dx) / length;
                if (butt) {
                    cover = std::clamp(half_width + 0.5 - across, 0.0, 1.0) * std::clamp(along + 0.5, 0.0, 1.0) *
                            std::clamp(length - along + 0.5, 0.0, 1.0);
                } else {
                    const double t = std::clamp(along, 0.0, length);
                    cover = std::clamp(half_width + 0.5 - std::hypot(cx - t * dx / length, cy - t * dy / length), 0.0, 1.0);
                }
            }
            float& a = c.at(x, y);
            a = std::max(a, float(cover));
        }
}

// matplotlib's dash patterns, in line widths (lines.dashed_pattern and the others).
std::vector<double> dash_pattern(Dash d) {
    switch (d) {
        case Dash::Dashed: return {3.7, 1.6};
        case Dash::Dotted: return {1, 1.65};
        case Dash::DashDot: return {6.4, 1.6, 1, 1.6};
        case Dash::Solid: break;
    }
    return {};
}

// A polyline in pixels, solid or dashed, into `c`.
void polyline(Coverage& c, const std::vector<Point>& points, Dash dash, double width_px, const Box& clip) {
    const double half = width_px / 2;
    std::vector<double> pattern = dash_pattern(dash);
    if (pattern.empty()) {
        for (size_t i = 0; i + 1 < points.size(); ++i) segment(c, points[i], points[i + 1], half, false, clip);
        if (points.size() == 1) segment(c, points[0], points[0], half, false, clip);
        return;
    }
    for (double& d : pattern) d *= width_px;
    size_t k = 0;
    double left = pattern[0];  // of the current dash or gap
    for (size_t i = 0; i + 1 < points.size(); ++i) {
        Point a = points[i];
        const Point b = points[i + 1];
        double rest = std::hypot(b.x - a.x, b.y - a.y);
        while (rest > 0) {
            const double step = std::min(rest, left);
            const double f = step / rest;
            const Point m{a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f};
            if (k % 2 == 0) segment(c, a, m, half, true, clip);
            a = m;
            rest -= step;
            left -= step;
            if (left <= 1e-9) k = (k + 1) % pattern.size(), left = pattern[k];
        }
    }
}

void fill(Image& image, const Box& box, Rgb colour, double alpha) {
    for (int y = int(std::lround(box.top)); y < int(std::lround(box.bottom)); ++y)
        for (int x = int(std::lround(box.left)); x < int(std::lround(box.right)); ++x) blend(image, x, y, colour, alpha);
}

// `c` laid on the image in `colour`, and cleared for the next lines.
void lay(Image& image, Coverage& c, Rgb colour, double alpha = 1) {
    for (int y = c.y0; y <= c.y1; ++y)
        for (int x = c.x0; x <= c.x1; ++x) {
            blend(image, x, y, colour, alpha * c.at(x, y));
            c.at(x, y) = 0;
        }
    c.x0 = c.y0 = 0, c.x1 = c.y1 = -1;
}

// A straight line of `width` points from p to q, laid at once (drawn into `scratch`, the image's size).
void rule(Image& image, Coverage& scratch, Point p, Point q, double width, Rgb colour, double alpha = 1) {
    segment(scratch, p, q, px(width) / 2, true, Box{0, 0, double(image.width), double(image.height)});
    lay(image, scratch, colour, alpha);
}

// An axis: its ticks over the data range with margins, their labels, and the power of ten they
// are given in when it is out of matplotlib's range for plain numbers (1e-5 to 1e6).
struct Axis {
    double lo = 0, hi = 1;  // the view's limits
    std::vector<double> ticks;
    std::vector<std::string> labels;
    std::string offset;  // e.g. "1e−6", drawn at the axis' end; empty when none
};

void data_range(double& lo, double& hi) {
    if (!(hi >= lo)) lo = 0, hi = 1;  // no points
    if (hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
        const double d = lo == 0 ? 1 : 0.05 * std::abs(lo);
        lo -= d, hi += d;
    } else {
        const double d = kMargin * (hi - lo);
        lo -= d, hi += d;
    }
}

Axis make_axis(double lo, double hi, double length_px, double points_per_label) {
    Axis a;
    a.lo = lo, a.hi = hi;
    const int intervals = std::clamp(int(length_px * 72 / kDpi / (kFontPt * points_per_label)), 1, 9);
    a.ticks = nice_ticks(lo, hi, intervals);
    const double step = a.ticks.size() > 1 ? a.ticks[1] - a.ticks[0] : std::max(std::abs(hi - lo), 1e-300);
    double most = 0;
    for (double t : a.ticks) most = std::max(most, std::abs(t));
    const int order = most > 0 ? int(std::floor(std::log10(most))) : 0;
    const double unit = order <= -5 || order >= 6 ? std::pow(10.0, order) : 1.0;
    if (unit != 1.0) a.offset = tick_label(order, 1).insert(0, "1e");
    for (double t : a.ticks) a.labels.push_back(tick_label(t / unit, step / unit));
    return a;
}

// The legend's box at matplotlib's place `code` (1 upper right ... 10 center) within `axes`.
Box legend_box(int code, const Box& axes, double w, double h, double gap) {
    const double l = axes.left + gap, r = axes.right - gap - w, cx = (axes.left + axes.right - w) / 2;
    const double t = axes.top + gap, b = axes.bottom - gap - h, cy = (axes.top + axes.bottom - h) / 2;
    double x = r, y = t;
    switch (code) {
        case 1: x = r, y = t; break;
        case 2: x = l, y = t; break;
        case 3: x = l, y = b; break;
        case 4: x = r, y = b; break;
        case 5: case 7: x = r, y = cy; break;
        case 6: x = l, y = cy; break;
        case 8: x = cx, y = b; break;
        case 9: x = cx, y = t; break;
        default: x = cx, y = cy; break;
    }
    return Box{x, y, x + w, y + h};
}

bool crosses(const Box& b, Point p, Point q) {
    if (b.contains(p) || b.contains(q)) return true;
    // Liang-Barsky: does the segment meet the box?
    double t0 = 0, t1 = 1;
    const double dx = q.x - p.x, dy = q.y - p.y;
    const std::array<double, 4> pp{-dx, dx, -dy, dy}, qq{p.x - b.left, b.right - p.x, p.y - b.top, b.bottom - p.y};
    for (size_t i = 0; i < 4; ++i) {
        if (pp[i] == 0) {
            if (qq[i] < 0) return false;
            continue;
        }
        const double r = qq[i] / pp[i];
        if (pp[i] < 0) t0 = std::max(t0, r);
        else t1 = std::min(t1, r);
        if (t0 > t1) return false;
    }
    return true;
}

}  // namespace

Rgb tab10(size_t i) {
    static constexpr std::array<Rgb, 10> kTab10{{{0x1f, 0x77, 0xb4}, {0xff, 0x7f, 0x0e}, {0x2c, 0xa0, 0x2c},
                                                  {0xd6, 0x27, 0x28}, {0x94, 0x67, 0xbd}, {0x8c, 0x56, 0x4b},
                                                  {0xe3, 0x77, 0xc2}, {0x7f, 0x7f, 0x7f}, {0xbc, 0xbd, 0x22},
                                                  {0x17, 0xbe, 0xcf}}};
    return kTab10[i % kTab10.size()];
}

std::vector<double> nice_ticks(double lo, double hi, int intervals) {
    if (!(std::isfinite(lo) && std::isfinite(hi) && hi > lo) || intervals < 1) return {};
    const double raw = (hi - lo) / intervals;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    double step = 10 * power;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * power >= raw * (1 - 1e-12)) {
            step = m * power;
            break;
        }
    std::vector<double> ticks;
    const double first = std::ceil(lo / step - 1e-9);
    for (double k = first; k * step <= hi + 1e-9 * step; k += 1) ticks.push_back(k * step == 0 ? 0.0 : k * step);
    return ticks;
}

std::string tick_label(double value, double step) {
    int decimals = 0;
    while (decimals < 12) {
        const double scaled = std::abs(step) * std::pow(10.0, decimals);
        if (std::abs(scaled - std::round(scaled)) <= 1e-6 * std::max(scaled, 1.0)) break;
        ++decimals;
    }
    if (std::abs(value) < 1e-9 * std::abs(step)) value = 0;
    std::string s = fmt::format("{:.{}f}", std::abs(value), decimals);
    return value < 0 ? "\u2212" + s : s;
}

Image draw_chart(const LineChart& chart, uint32_t width, uint32_t height) {
    Image image(width, height);
    std::fill(image.rgb.begin(), image.rgb.end(), uint8_t(255));
    const Text font(kFontPt), title_font(kTitlePt), legend_font(chart.small_legend ? kSmallPt : kFontPt);
    Coverage scratch{int(width), int(height)};  // each line's coverage before it is laid

    double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
    for (const ChartSeries& s : chart.series)
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!drawable(s.x[i]) || !drawable(s.y[i])) continue;
            x_lo = std::min(x_lo, s.x[i]), x_hi = std::max(x_hi, s.x[i]);
            y_lo = std::min(y_lo, s.y[i]), y_hi = std::max(y_hi, s.y[i]);
        }
    data_range(x_lo, x_hi);
    data_range(y_lo, y_hi);

    // tight_layout: the axes box fitted to the labels around it, three times over, as the ticks
    // (and so the labels' widths) follow the box's size.
    const double pad = px(kLayoutPad), tick = px(kTickLength), tick_pad = px(kTickPad), label_pad = px(kLabelPad);
    Box axes{pad + 60, pad + 30, width - pad - 10.0, height - pad - 40.0};
    Axis xa, ya;
    double widest = 0;  // of the y labels
    for (int round = 0; round < 3; ++round) {
        xa = make_axis(x_lo, x_hi, axes.right - axes.left, 3);
        ya = make_axis(y_lo, y_hi, axes.bottom - axes.top, 2);
        widest = 0;
        for (const std::string& l : ya.labels) widest = std::max(widest, font.width(l));
        const double left = pad + (chart.y_label.empty() ? 0 : font.height() + label_pad) + widest + tick_pad + tick;
        const double bottom = pad + (chart.x_label.empty() ? 0 : font.height() + label_pad) + font.height() + tick_pad + tick;
        const double top = pad + (chart.title.empty() ? 0 : title_font.height() + px(kTitlePad)) +
                           (ya.offset.empty() ? 0 : font.height());
        // The last x label may reach past the axes' right end by what half of it overhangs its tick.
        const double room = xa.ticks.empty() ? 0 : (xa.hi - xa.ticks.back()) / (xa.hi - xa.lo) * (axes.right - axes.left);
        const double over = xa.labels.empty() ? 0 : std::max(font.width(xa.labels.back()) / 2 - room, 0.0);
        axes = Box{std::round(left), std::round(top), std::round(width - pad - over), std::round(height - bottom)};
    }
    const double aw = axes.right - axes.left, ah = axes.bottom - axes.top;
    const auto to_px = [&](double x, double y) {
        return Point{axes.left + (x - xa.lo) / (xa.hi - xa.lo) * aw, axes.bottom - (y - ya.lo) / (ya.hi - ya.lo) * ah};
    };

    // The grid, below the lines (matplotlib's axes.axisbelow = "line").
    const Rgb grid{0xb0, 0xb0, 0xb0};
    for (double t : xa.ticks) {
        const double x = to_px(t, 0).x;
        rule(image, scratch, {x, axes.top}, {x, axes.bottom}, kAxisWidth, grid, 0.3);
    }
    for (double t : ya.ticks) {
        const double y = to_px(0, t).y;
        rule(image, scratch, {axes.left, y}, {axes.right, y}, kAxisWidth, grid, 0.3);
    }

    // The series, each laid at once from its own coverage.
    std::vector<std::vector<Point>> drawn(chart.series.size());
    for (size_t k = 0; k < chart.series.size(); ++k) {
        const ChartSeries& s = chart.series[k];
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
            if (drawable(s.x[i]) && drawable(s.y[i])) drawn[k].push_back(to_px(s.x[i], s.y[i]));
        if (drawn[k].empty()) continue;
        polyline(scratch, drawn[k], s.dash, px(s.width), axes);
        lay(image, scratch, s.colour);
    }

    // Spines, ticks and their labels.
    rule(image, scratch, {axes.left, axes.top}, {axes.right, axes.top}, kAxisWidth, kBlack);
    rule(image, scratch, {axes.left, axes.bottom}, {axes.right, axes.bottom}, kAxisWidth, kBlack);
    rule(image, scratch, {axes.left, axes.top}, {axes.left, axes.bottom}, kAxisWidth, kBlack);
    rule(image, scratch, {axes.right, axes.top}, {axes.right, axes.bottom}, kAxisWidth, kBlack);
    for (size_t i = 0; i < xa.ticks.size(); ++i) {
        const double x = to_px(xa.ticks[i], 0).x;
        rule(image, scratch, {x, axes.bottom}, {x, axes.bottom + tick}, kAxisWidth, kBlack);
        font.draw(image, x - font.width(xa.labels[i]) / 2, axes.bottom + tick + tick_pad + font.ascent(), xa.labels[i],
                  kBlack);
    }
    for (size_t i = 0; i < ya.ticks.size(); ++i) {
        const double y = to_px(0, ya.ticks[i]).y;
        rule(image, scratch, {axes.left - tick, y}, {axes.left, y}, kAxisWidth, kBlack);
        // Centred on the tick by the digits' height (0.73 em in DejaVu Sans).
        font.draw(image, axes.left - tick - tick_pad - font.width(ya.labels[i]), y + 0.365 * px(kFontPt), ya.labels[i],
                  kBlack);
    }
    if (!ya.offset.empty()) font.draw(image, axes.left, axes.top - font.descent() - 2, ya.offset, kBlack);
    if (!xa.offset.empty())
        font.draw(image, axes.right - font.width(xa.offset), height - pad + font.ascent(), xa.offset, kBlack);

    // The legend where it covers the fewest points and crossings of the lines (matplotlib's "best").
    std::vector<size_t> entries;
    for (size_t k = 0; k < chart.series.size(); ++k)
        if (!chart.series[k].label.empty()) entries.push_back(k);
    if (!entries.empty()) {
        const double em = px(chart.small_legend ? kSmallPt : kFontPt), row = legend_font.height();
        const double border = 0.4 * em, spacing = 0.5 * em, handle = 2.0 * em, handle_pad = 0.8 * em;
        double text = chart.legend_title.empty() ? 0 : legend_font.width(chart.legend_title);
        for (size_t k : entries) text = std::max(text, handle + handle_pad + legend_font.width(chart.series[k].label));
        const double rows = double(entries.size()) + (chart.legend_title.empty() ? 0 : 1);
        const double w = 2 * border + text, h = 2 * border + rows * row + (rows - 1) * spacing;
        Box best{};
        size_t least = SIZE_MAX;
        for (int code = 1; code <= 10; ++code) {
            const Box b = legend_box(code, axes, w, h, 0.5 * em);
            size_t bad = 0;
            for (const std::vector<Point>& line : drawn) {
                for (const Point& p : line) bad += b.contains(p);
                for (size_t i = 0; i + 1 < line.size(); ++i) bad += crosses(b, line[i], line[i + 1]);
            }
            if (bad < least) least = bad, best = b;
        }
        fill(image, best, Rgb{255, 255, 255}, 0.8);
        const Rgb edge{0xcc, 0xcc, 0xcc};
        rule(image, scratch, {best.left, best.top}, {best.right, best.top}, kAxisWidth, edge);
        rule(image, scratch, {best.left, best.bottom}, {best.right, best.bottom}, kAxisWidth, edge);
        rule(image, scratch, {best.left, best.top}, {best.left, best.bottom}, kAxisWidth, edge);
        rule(image, scratch, {best.right, best.top}, {best.right, best.bottom}, kAxisWidth, edge);
        double y = best.top + border;
        if (!chart.legend_title.empty()) {
            legend_font.draw(image, (best.left + best.right - legend_font.width(chart.legend_title)) / 2,
                             y + legend_font.ascent(), chart.legend_title, kBlack);
            y += row + spacing;
        }
        for (size_t k : entries) {
            const ChartSeries& s = chart.series[k];
            const double middle = y + row / 2;
            polyline(scratch, {{best.left + border, middle}, {best.left + border + handle, middle}}, s.dash,
                     px(s.width), Box{0, 0, double(width), double(height)});
            lay(image, scratch, s.colour);
            legend_font.draw(image, best.left + border + handle + handle_pad, y + legend_font.ascent(), s.label, kBlack);
            y += row + spacing;
        }
    }

    // The title and the axes' labels.
    if (!chart.title.empty())
        title_font.draw(image, axes.left + (aw - title_font.width(chart.title)) / 2,
                        axes.top - px(kTitlePad) - title_font.descent() - (ya.offset.empty() ? 0 : font.height()),
                        chart.title, kBlack);
    if (!chart.x_label.empty())
        font.draw(image, axes.left + (aw - font.width(chart.x_label)) / 2,
                  axes.bottom + tick + tick_pad + font.height() + label_pad + font.ascent(), chart.x_label, kBlack);
    if (!chart.y_label.empty()) {
        font.draw_up(image, axes.left - tick - tick_pad - widest - label_pad - font.height(), axes.top + ah / 2,
                     chart.y_label, kBlack);
    }
    return image;
}

}  // namespace shatter
