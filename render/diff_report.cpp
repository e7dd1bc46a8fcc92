#include "render/diff_report.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "render/png_io.h"

namespace shatter {

namespace fs = std::filesystem;

namespace {

std::set<std::string> png_names(const std::string& dir) {
    std::set<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".png" && !it->is_directory()) names.insert(it->path().filename().string());
    if (ec) throw_input_error(dir, fmt::format("cannot list the directory ({})", ec.message()), "check the path");
    return names;
}

ImageDiff compare_files(const std::string& name, const std::string& expected, const std::string& actual,
                        const DiffTolerance& tolerance, const std::string& report_dir) {
    const Image a = load_png(expected), b = load_png(actual);
    if (a.width != b.width || a.height != b.height)
        throw_input_error(actual, fmt::format("the image is {}x{} but {} is {}x{}", b.width, b.height, expected, a.width,
                                              a.height),
                          "compare renders of the same --size");
    ImageDiff d;
    d.name = name;
    d.metrics = compare_images(a, b, tolerance.threshold);
    d.failures = tolerance_failures(d.metrics, tolerance);
    if (!d.failures.empty() && !report_dir.empty()) {
        make_directories(report_dir);
        d.heat_map = (fs::path(report_dir) / (fs::path(name).stem().string() + ".heat.png")).string();
        save_png(d.heat_map, heat_map(a, b));
    }
    return d;
}

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

}  // namespace

DiffSummary diff_paths(const std::string& expected, const std::string& actual, const DiffTolerance& tolerance,
                       const std::string& report_dir) {
    DiffSummary s{expected, actual, tolerance, {}, 0};
    for (const std::string& p : {expected, actual})
        if (!fs::exists(p)) throw_input_error(p, "no such file or directory", "give an existing image or directory");
    const bool dirs = fs::is_directory(expected);
    if (dirs != fs::is_directory(actual))
        throw_input_error(actual, fmt::format("one of {} and {} is a directory and the other is not", expected, actual),
                          "compare two images or two directories of frames");
    if (!dirs) {
        s.images.push_back(compare_files(fs::path(actual).filename().string(), expected, actual, tolerance, report_dir));
    } else {
        const std::set<std::string> a = png_names(expected), b = png_names(actual);
        for (const std::string& n : a)
            if (!b.count(n)) throw_input_error((fs::path(actual) / n).string(), fmt::format("missing: {} has it", expected),
                                               "render the missing frames (shatter render --frames)");
        for (const std::string& n : b)
            if (!a.count(n)) throw_input_error((fs::path(expected) / n).string(), fmt::format("missing: {} has it", actual),
                                               "compare directories that hold the same frames");
        if (a.empty()) throw_input_error(expected, "no .png images in the directory", "give a directory of frames");
        for (const std::string& n : a)
            s.images.push_back(compare_files(n, (fs::path(expected) / n).string(), (fs::path(actual) / n).string(),
                                             tolerance, report_dir));
    }
    for (const ImageDiff& d : s.images) s.failed += !d.failures.empty();
    return s;
}

std::string diff_summary_json(const DiffSummary& s) {
    nlohmann::ordered_json j;
    j["expected"] = s.expected;
    j["actual"] = s.actual;
    j["tolerance"] = {{"max_channel_diff", s.tolerance.max_channel_diff}, {"max_rmse", s.tolerance.max_rmse},
                      {"min_psnr", s.tolerance.min_psnr},                 {"min_ssim", s.tolerance.min_ssim},
                      {"threshold", s.tolerance.threshold},               {"max_fraction", s.tolerance.max_fraction}};
    j["images"] = s.images.size();
    j["failed"] = s.failed;
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const ImageDiff& d : s.images) {
        const DiffMetrics& m = d.metrics;
        nlohmann::ordered_json e;
        e["name"] = d.name;
        e["pass"] = d.failures.empty();
        e["max_channel_diff"] = m.max_channel_diff;
        e["rmse"] = m.rmse;
        e["psnr"] = std::isfinite(m.psnr) ? nlohmann::ordered_json(m.psnr) : nlohmann::ordered_json(nullptr);  // null: identical
        e["ssim"] = m.ssim;
        e["fraction_over_threshold"] = m.fraction_over;
        e["failures"] = d.failures;
        if (!d.heat_map.empty()) e["heat_map"] = d.heat_map;
        list.push_back(e);
    }
    j["results"] = list;
    return j.dump(2) + "\n";
}

std::string diff_junit_xml(const DiffSummary& s) {
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += fmt::format("<testsuites tests=\"{0}\" failures=\"{1}\">\n<testsuite name=\"shatter diff {2}\" tests=\"{0}\" "
                       "failures=\"{1}\">\n", s.images.size(), s.failed, xml_escape(s.actual));
    for (const ImageDiff& d : s.images) {
        const DiffMetrics& m = d.metrics;
        out += fmt::format("  <testcase classname=\"shatter.diff\" name=\"{}\">\n", xml_escape(d.name));
        if (!d.failures.empty()) {
            std::string text;
            for (const std::string& f : d.failures) text += f + "\n";
            out += fmt::format("    <failure message=\"{}\">{}</failure>\n", xml_escape(d.failures.front()), xml_escape(text));
        }
        out += fmt::format("    <system-out>max {} rmse {:.4g} psnr {:.4g} ssim {:.6g} over {:.4g}</system-out>\n",
                           m.max_channel_diff, m.rmse, m.psnr, m.ssim, m.fraction_over);
        out += "  </testcase>\n";
    }
    return out + "</testsuite>\n</testsuites>\n";
}

}  // namespace shatter
