// Contact sheets and strips: the frames chosen, each tile's colour at its predicted place, label
// bands with exactly the font's lit pixels at the predicted position, the box filter's exact
// means, and the same bytes twice.
#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/error.h"
#include "pipeline/font.h"
#include "pipeline/sheets.h"
#include "render/png_io.h"
#include "support/frames_appearing.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::FramesAppearing;
using testing_support::TempDir;

struct Colour {
    uint8_t r, g, b;
    bool operator==(const Colour&) const = default;
};
std::ostream& operator<<(std::ostream& os, const Colour& c) { return os << int(c.r) << "," << int(c.g) << "," << int(c.b); }

Colour at(const Image& img, uint32_t x, uint32_t y) {
    const uint8_t* p = img.pixel(x, y);
    return {p[0], p[1], p[2]};
}
const Colour kBackground{kSheetBackground[0], kSheetBackground[1], kSheetBackground[2]};
const Colour kBand{kLabelBandColour[0], kLabelBandColour[1], kLabelBandColour[2]};
const Colour kText{kLabelColour[0], kLabelColour[1], kLabelColour[2]};

Colour frame_colour(uint32_t i) { return {uint8_t(10 * i), uint8_t(250 - 10 * i), 77}; }

Image solid(uint32_t w, uint32_t h, Colour c) {
    Image img(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            img.pixel(x, y)[0] = c.r;
            img.pixel(x, y)[1] = c.g;
            img.pixel(x, y)[2] = c.b;
        }
    return img;
}

void write_frames(const fs::path& dir, uint32_t count, uint32_t w, uint32_t h) {
    fs::create_directories(dir);
    for (uint32_t i = 0; i < count; ++i) save_png((dir / fmt::format("frame_{:05d}.png", i)).string(), solid(w, h, frame_colour(i)));
}

// Lit pixels of an ASCII label at scale `scale`, from the font's glyph table.
int lit_pixels(const std::string& label, int scale) {
    int n = 0;
    for (char c : label)
        for (int row = 0; row < kGlyphHeight; ++row) n += std::popcount(glyph_rows(char32_t(c))[row]);
    return n * scale * scale;
}

// Pixels of `colour` in the rectangle.
int count(const Image& img, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, Colour colour) {
    int n = 0;
    for (uint32_t y = y0; y < y0 + h; ++y)
        for (uint32_t x = x0; x < x0 + w; ++x) n += at(img, x, y) == colour;
    return n;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Sheets, ContactSheetFramesAreEvenlySpacedWithFirstAndLast) {
    EXPECT_EQ(contact_sheet_frames(120, 12), (std::vector<uint32_t>{0, 11, 22, 32, 43, 54, 65, 76, 87, 97, 108, 119}));
    EXPECT_EQ(contact_sheet_frames(24, 6), (std::vector<uint32_t>{0, 5, 9, 14, 18, 23}));
    EXPECT_EQ(contact_sheet_frames(5, 12), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(contact_sheet_frames(1, 12), (std::vector<uint32_t>{0}));
}

TEST(Sheets, BoxResizeGivesAreaWeightedMeans) {
    Image row(3, 1);
    const uint8_t values[3] = {0, 90, 255};
    for (uint32_t x = 0; x < 3; ++x) row.pixel(x, 0)[0] = row.pixel(x, 0)[1] = row.pixel(x, 0)[2] = values[x];
    const Image half = box_resize(row, 2, 1);
    EXPECT_EQ(half.pixel(0, 0)[0], 30);   // (0 * 2 + 90 * 1) / 3
    EXPECT_EQ(half.pixel(1, 0)[0], 200);  // (90 * 1 + 255 * 2) / 3
    Image block(4, 2);
    for (uint32_t x = 0; x < 4; ++x) block.pixel(x, 0)[1] = uint8_t(x * 10), block.pixel(x, 1)[1] = uint8_t(x * 10 + 1);
    const Image quarter = box_resize(block, 2, 1);
    EXPECT_EQ(quarter.pixel(0, 0)[1], 6);   // (0 + 10 + 1 + 11) / 4 = 5.5, rounded half up
    EXPECT_EQ(quarter.pixel(1, 0)[1], 26);  // (20 + 30 + 21 + 31) / 4 = 25.5
    EXPECT_EQ(box_resize(block, 4, 2).rgb, block.rgb);  // same size: unchanged
}

TEST(Sheets, FontMeasuresUtf8AndBoxesUnknownCharacters) {
    EXPECT_EQ(text_width("t = 1", 2), (5 * kGlyphAdvance - 1) * 2);
    EXPECT_EQ(text_width("\xce\xb1 = 2", 1), 5 * kGlyphAdvance - 1);  // alpha is one glyph
    EXPECT_EQ(text_width("", 3), 0);
    EXPECT_EQ(glyph_rows(U'\u2603'), glyph_rows(U'\u2604'));  // both the missing-glyph box
    EXPECT_NE(glyph_rows(U'a'), glyph_rows(U'\u2603'));
}

TEST(Sheets, ContactSheetPutsEachChosenFrameAndItsTimeLabelInPlace) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 24, 320, 240);
    const ContactSheetOptions options{.columns = 3, .rows = 2, .tile_width = 160};
    write_contact_sheet((tmp.path() / "frames").string(), 24, 12.0, tmp.file("sheet.png"), options);
    const Image sheet = load_png(tmp.file("sheet.png"));
    const uint32_t tw = 160, th = 120, gap = kSheetGap;  // 320x240 scaled to 160 wide
    ASSERT_EQ(sheet.width, 3 * tw + 4 * gap);
    ASSERT_EQ(sheet.height, 2 * (th + kLabelBand) + 3 * gap);
    const uint32_t shown[6] = {0, 5, 9, 14, 18, 23};
    const char* labels[6] = {"t = 0.00 s", "t = 0.42 s", "t = 0.75 s", "t = 1.17 s", "t = 1.50 s", "t = 1.92 s"};
    for (uint32_t i = 0; i < 6; ++i) {
        SCOPED_TRACE(i);
        const uint32_t x0 = gap + (i % 3) * (tw + gap), y0 = gap + (i / 3) * (th + kLabelBand + gap);
        EXPECT_EQ(count(sheet, x0, y0, tw, th, frame_colour(shown[i])), int(tw * th));  // the whole tile
        EXPECT_EQ(at(sheet, x0 - 1, y0), kBackground);
        EXPECT_EQ(at(sheet, x0, y0 - 1), kBackground);
        // The band: band colour around exactly the label's lit pixels, 't' first: its top row
        // lights column 1, i.e. pixels 2..3 right of the centred text's left edge.
        const uint32_t band_y = y0 + th;
        const int text_x = (int(tw) - text_width(labels[i], kLabelScale)) / 2;
        EXPECT_EQ(count(sheet, x0, band_y, tw, kLabelBand, kText), lit_pixels(labels[i], kLabelScale));
        EXPECT_EQ(count(sheet, x0, band_y, tw, kLabelBand, kBand) + lit_pixels(labels[i], kLabelScale),
                  int(tw * kLabelBand));
        EXPECT_EQ(at(sheet, x0 + uint32_t(text_x) + 2, band_y + kLabelPadding), kText);
        EXPECT_EQ(at(sheet, x0 + uint32_t(text_x) + 1, band_y + kLabelPadding), kBand);
        EXPECT_EQ(at(sheet, x0, band_y + kLabelBand), kBackground);
    }
}

TEST(Sheets, ContactSheetOfFewerFramesThanTilesLeavesTheRestEmpty) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 2, 64, 32);
    write_contact_sheet((tmp.path() / "frames").string(), 2, 30.0, tmp.file("sheet.png"),
                        {.columns = 2, .rows = 2, .tile_width = 32});
    const Image sheet = load_png(tmp.file("sheet.png"));
    const uint32_t tw = 32, th = 16, gap = kSheetGap;
    EXPECT_EQ(at(sheet, gap + tw / 2, gap + th / 2), frame_colour(0));
    EXPECT_EQ(at(sheet, 2 * gap + tw + tw / 2, gap + th / 2), frame_colour(1));
    EXPECT_EQ(at(sheet, gap + tw / 2, 2 * gap + th + kLabelBand + th / 2), kBackground);
}

TEST(Sheets, SameFramesGiveTheSameBytes) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 8, 96, 64);
    write_contact_sheet((tmp.path() / "frames").string(), 8, 30.0, tmp.file("a.png"), {.columns = 2, .rows = 2, .tile_width = 48});
    write_contact_sheet((tmp.path() / "frames").string(), 8, 30.0, tmp.file("b.png"), {.columns = 2, .rows = 2, .tile_width = 48});
    EXPECT_EQ(slurp(tmp.file("a.png")), slurp(tmp.file("b.png")));
    const std::vector<StripPanel> panels = {{tmp.file("frames/frame_00001.png"), "alpha = 0.5"},
                                            {tmp.file("frames/frame_00002.png"), "alpha = 2"}};
    write_strip(panels, tmp.file("s1.png"), 64);
    write_strip(panels, tmp.file("s2.png"), 64);
    EXPECT_EQ(slurp(tmp.file("s1.png")), slurp(tmp.file("s2.png")));
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"a.png", "b.png", "frames", "s1.png", "s2.png"}));
}

TEST(Sheets, StripPlacesPanelsSideBySideWithLabelsUnderTheTallest) {
    TempDir tmp;
    save_png(tmp.file("wide.png"), solid(200, 100, {200, 30, 30}));
    save_png(tmp.file("wider.png"), solid(200, 50, {30, 30, 200}));
    const std::string la = "alpha = 0.5", lb = "alpha = 2";
    write_strip({{tmp.file("wide.png"), la}, {tmp.file("wider.png"), lb}}, tmp.file("strip.png"), 160);
    const Image strip = load_png(tmp.file("strip.png"));
    const uint32_t pw = 160, gap = kSheetGap, tallest = 80;  // 200x100 -> 160x80, 200x50 -> 160x40
    ASSERT_EQ(strip.width, 2 * pw + 3 * gap);
    ASSERT_EQ(strip.height, tallest + kLabelBand + 2 * gap);
    EXPECT_EQ(count(strip, gap, gap, pw, 80, {200, 30, 30}), int(pw * 80));
    EXPECT_EQ(count(strip, 2 * gap + pw, gap, pw, 40, {30, 30, 200}), int(pw * 40));
    EXPECT_EQ(at(strip, 2 * gap + pw, gap + 40), kBackground);  // under the shorter panel
    EXPECT_EQ(count(strip, gap, gap + tallest, pw, kLabelBand, kText), lit_pixels(la, kLabelScale));
    EXPECT_EQ(count(strip, 2 * gap + pw, gap + tallest, pw, kLabelBand, kText), lit_pixels(lb, kLabelScale));
}

TEST(Sheets, MissingFrameIsBadInputNamingIt) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 3, 32, 32);
    try {
        write_contact_sheet((tmp.path() / "frames").string(), 4, 30.0, tmp.file("sheet.png"), {.columns = 2, .rows = 2, .tile_width = 16});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("frame_00003.png"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(tmp.file("sheet.png")));
    EXPECT_THROW(write_strip({}, tmp.file("strip.png")), Error);
}

// As `shatter run` makes the sheet beside render: the frames appear one by one, each shown frame
// read once it is there, and the bytes are those of a sheet made after the last frame.
TEST(Sheets, FramesTakenAsTheyAppearGiveTheBytesOfFramesThatWereAllThere) {
    TempDir tmp;
    write_frames(tmp.path() / "all", 8, 96, 64);
    const ContactSheetOptions options{.columns = 2, .rows = 2, .tile_width = 48};
    write_contact_sheet((tmp.path() / "all").string(), 8, 30.0, tmp.file("all.png"), options);
    const fs::path later = tmp.path() / "later";
    FramesAppearing render(tmp.path() / "all", later, 8, std::chrono::milliseconds(10));
    std::vector<uint32_t> asked;
    write_contact_sheet(later.string(), 8, 30.0, tmp.file("later.png"), options, [&](uint32_t f) {
        asked.push_back(f);
        return render.ready(f);
    });
    render.join();
    EXPECT_EQ(asked, contact_sheet_frames(8, 4));  // the shown frames, in order, each once
    EXPECT_EQ(slurp(tmp.file("later.png")), slurp(tmp.file("all.png")));
    // A shown frame that never comes (its render failed): bad input naming it, no sheet.
    try {
        write_contact_sheet(later.string(), 8, 30.0, tmp.file("never.png"), options, [](uint32_t f) { return f < 7; });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("frame_00007.png"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(tmp.file("never.png")));
}

}  // namespace
}  // namespace shatter
