// Contact sheets and strips, composed in memory from PNG frames and written with png_io.
//
// Scaling is an exact box filter in integer arithmetic: along one axis, output pixel o of n
// covers source interval [o * N / n, (o + 1) * N / n); measured in units of 1 / n source
// pixels that is [o * N, (o + 1) * N) against source pixel s's [s * n, (s + 1) * n), so every
// weight is the integer length of an overlap and the weights of one output pixel sum to N. The
// two passes multiply, and one rounded division at the end gives the mean: the same bytes on
// every machine and compiler. (Averaging sRGB values rather than linear light darkens fine
// bright detail slightly; for thumbnails this is the usual trade.)
#include "pipeline/sheets.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "pipeline/font.h"
#include "render/png_io.h"

namespace shatter {

namespace {

struct Tap {
    uint32_t source;
    uint32_t weight;
};

// For each of `n` output pixels along an axis of `N` source pixels, its source pixels and weights.
std::vector<std::vector<Tap>> box_taps(uint32_t N, uint32_t n) {
    std::vector<std::vector<Tap>> taps(n);
    for (uint32_t o = 0; o < n; ++o) {
        const uint64_t begin = uint64_t(o) * N, end = uint64_t(o + 1) * N;
        for (uint64_t s = begin / n; s < N && s * n < end; ++s) {
            const uint64_t overlap = std::min(end, (s + 1) * n) - std::max(begin, s * n);
            if (overlap > 0) taps[o].push_back({uint32_t(s), uint32_t(overlap)});
        }
    }
    return taps;
}

void fill(Image& image, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, const uint8_t colour[3]) {
    for (uint32_t y = y0; y < std::min(y0 + h, image.height); ++y)
        for (uint32_t x = x0; x < std::min(x0 + w, image.width); ++x) std::copy(colour, colour + 3, image.pixel(x, y));
}

void paste(Image& canvas, const Image& tile, uint32_t x0, uint32_t y0) {
    for (uint32_t y = 0; y < tile.height; ++y)
        std::copy(tile.pixel(0, y), tile.pixel(0, y) + size_t(tile.width) * 3, canvas.pixel(x0, y0 + y));
}

// The band under a tile at (x0, band_y), `width` wide, with `label` centred in it (a label wider
// than the tile is cut at the tile's edge).
void draw_label(Image& canvas, uint32_t x0, uint32_t band_y, uint32_t width, const std::string& label) {
    Image band(width, kLabelBand);
    fill(band, 0, 0, width, kLabelBand, kLabelBandColour);
    const int x = std::max(int(kLabelPadding), (int(width) - text_width(label, kLabelScale)) / 2);
    draw_text(band, x, int(kLabelPadding), label, kLabelScale, Rgb{kLabelColour[0], kLabelColour[1], kLabelColour[2]});
    paste(canvas, band, x0, band_y);
}

uint32_t scaled_height(const Image& frame, uint32_t width) {
    return std::max<uint32_t>(1, uint32_t((uint64_t(frame.height) * width + frame.width / 2) / frame.width));
}

void check_range(const char* field, uint32_t value, uint32_t low, uint32_t high) {
    if (value < low || value > high)
        throw_input_error(field, fmt::format("{} is outside [{}, {}]", value, low, high),
                          fmt::format("give a value in [{}, {}]", low, high));
}

}  // namespace

Image box_resize(const Image& source, uint32_t width, uint32_t height) {
    const auto columns = box_taps(source.width, width), rows = box_taps(source.height, height);
    // Horizontal pass: sums scaled by source.width.
    std::vector<uint32_t> wide(size_t(width) * source.height * 3);
    for (uint32_t y = 0; y < source.height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                uint32_t sum = 0;
                for (const Tap& t : columns[x]) sum += uint32_t(source.pixel(t.source, y)[c]) * t.weight;
                wide[(size_t(y) * width + x) * 3 + size_t(c)] = sum;
            }
    // Vertical pass and the one division by source.width * source.height.
    Image out(width, height);
    const uint64_t total = uint64_t(source.width) * source.height;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                uint64_t sum = 0;
                for (const Tap& t : rows[y])
                    sum += uint64_t(wide[(size_t(t.source) * width + x) * 3 + size_t(c)]) * t.weight;
                out.pixel(x, y)[c] = uint8_t((sum + total / 2) / total);
            }
    return out;
}

std::vector<uint32_t> contact_sheet_frames(uint32_t frames, uint32_t tiles) {
    const uint32_t n = std::min(frames, tiles);
    std::vector<uint32_t> out;
    if (n == 1) out.push_back(0);
    for (uint32_t i = 0; n > 1 && i < n; ++i)
        out.push_back(uint32_t((uint64_t(i) * (frames - 1) + (n - 1) / 2) / (n - 1)));
    return out;
}

void write_contact_sheet(const std::string& frames_dir, uint32_t frames, double fps, const std::string& png_path,
                         const ContactSheetOptions& options, const std::function<bool(uint32_t frame)>& ready) {
    check_range("contact sheet columns", options.columns, 1, 64);
    check_range("contact sheet rows", options.rows, 1, 64);
    check_range("contact sheet tile_width", options.tile_width, 16, 4096);
    if (frames == 0)
        throw_input_error(frames_dir, "no frames for a contact sheet (0 frames)", "render the frames first");
    if (!(fps > 0.0)) throw_input_error(frames_dir, fmt::format("frame rate {} is not positive", fps), "give fps > 0");

    const std::vector<uint32_t> shown = contact_sheet_frames(frames, options.columns * options.rows);
    const uint32_t tw = options.tile_width, gap = kSheetGap;
    Image canvas;
    uint32_t th = 0;
    for (size_t i = 0; i < shown.size(); ++i) {
        const std::string path = fmt::format("{}/frame_{:05d}.png", frames_dir, shown[i]);
        if (ready && !ready(shown[i]))
            throw_input_error(path, fmt::format("frame {} of {} was not drawn", shown[i], frames),
                              "render all frames first (shatter render)");
        const Image frame = load_png(path);
        if (i == 0) {
            th = scaled_height(frame, tw);
            canvas = Image(options.columns * tw + (options.columns + 1) * gap,
                           options.rows * (th + kLabelBand) + (options.rows + 1) * gap);
            fill(canvas, 0, 0, canvas.width, canvas.height, kSheetBackground);
        }
        const uint32_t col = uint32_t(i) % options.columns, row = uint32_t(i) / options.columns;
        const uint32_t x0 = gap + col * (tw + gap), y0 = gap + row * (th + kLabelBand + gap);
        paste(canvas, box_resize(frame, tw, th), x0, y0);
        draw_label(canvas, x0, y0 + th, tw, fmt::format("t = {:.2f} s", shown[i] / fps));
    }
    save_png(png_path, canvas);
}

void write_strip(const std::vector<StripPanel>& panels, const std::string& png_path, uint32_t panel_width) {
    if (panels.empty()) throw_input_error(png_path, "a strip needs at least one panel", "give one frame per run");
    check_range("strip panel_width", panel_width, 16, 4096);
    std::vector<Image> tiles;
    uint32_t tallest = 0;
    for (const StripPanel& p : panels) {
        const Image frame = load_png(p.frame_png);
        tiles.push_back(box_resize(frame, panel_width, scaled_height(frame, panel_width)));
        tallest = std::max(tallest, tiles.back().height);
    }
    const uint32_t n = uint32_t(panels.size()), gap = kSheetGap;
    Image canvas(n * panel_width + (n + 1) * gap, tallest + kLabelBand + 2 * gap);
    fill(canvas, 0, 0, canvas.width, canvas.height, kSheetBackground);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t x0 = gap + i * (panel_width + gap);
        paste(canvas, tiles[i], x0, gap);  // top-aligned; the bands line up under the tallest
        draw_label(canvas, x0, gap + tallest, panel_width, panels[i].label);
    }
    save_png(png_path, canvas);
}

}  // namespace shatter
