// Images made of frames: the contact sheet of one run (a grid of frames) and the strip of a
// sweep (one panel per value at the same frame, labelled, as in the paper's figures).
// Deterministic bytes; written atomically.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/image.h"

namespace shatter {

// Layout of both images (unit: pixels): tiles sit kSheetGap apart and from the border on a
// kSheetBackground ground; under each tile a kLabelBand-high band of kLabelBandColour carries its
// label in kLabelColour, the 5x7 font (pipeline/font.h) at scale kLabelScale, centred.
inline constexpr uint32_t kSheetGap = 8;
inline constexpr int kLabelScale = 2;
inline constexpr uint32_t kLabelPadding = 6;                    // above and below the text
inline constexpr uint32_t kLabelBand = 7 * kLabelScale + 2 * kLabelPadding;  // 26
inline constexpr uint8_t kSheetBackground[3] = {12, 12, 12};
inline constexpr uint8_t kLabelBandColour[3] = {32, 32, 36};
inline constexpr uint8_t kLabelColour[3] = {235, 235, 235};

// `source` scaled to width x height by an exact box filter: each output pixel is the
// area-weighted mean of the source pixels it covers (integer weights, rounded once), in sRGB.
Image box_resize(const Image& source, uint32_t width, uint32_t height);

// The frames a contact sheet of `tiles` tiles shows out of [0, frames): evenly spaced, first and
// last included, round(i * (frames - 1) / (tiles - 1)); at most `frames` of them.
std::vector<uint32_t> contact_sheet_frames(uint32_t frames, uint32_t tiles);

struct ContactSheetOptions {
    uint32_t columns = 4;
    uint32_t rows = 3;
    uint32_t tile_width = 320;  // (unit: pixels) each frame scaled to this width
};

// A grid of columns x rows frames evenly spaced over [0, frames) of FRAMES_DIR
// (frame_NNNNN.png), each labelled with its time "t = 1.25 s" (frame / fps). Tiles are
// tile_width wide and as high as the first frame's aspect ratio makes them. Throws
// Error(BadInput) for a missing or unreadable frame, Error(Io) when the sheet cannot be written.
// Given `ready`, the frames need not be there yet (the sheet is made while render draws them):
// each shown frame is read once ready(i) returns true, and ready(i) returning false (the frame will
// never come) is a missing frame. The bytes are the same either way.
void write_contact_sheet(const std::string& frames_dir, uint32_t frames, double fps, const std::string& png_path,
                         const ContactSheetOptions& options = {},
                         const std::function<bool(uint32_t frame)>& ready = {});

struct StripPanel {
    std::string frame_png;  // the frame to show
    std::string label;      // e.g. "alpha = 0.5"
};

// The panels side by side (each scaled to `panel_width`, keeping its aspect ratio, top-aligned),
// each with its label in a band under the tallest. Errors as for the contact sheet.
void write_strip(const std::vector<StripPanel>& panels, const std::string& png_path, uint32_t panel_width = 480);

}  // namespace shatter
