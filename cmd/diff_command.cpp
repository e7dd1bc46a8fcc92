// shatter diff EXPECTED ACTUAL [--max-rmse L] [--min-ssim S] [--threshold L --max-fraction F] ...
// Exit codes (the command's own): 0 within tolerance, 1 differ, 2 error (a missing frame, a size
// mismatch, an unreadable file, a bad flag).
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cmd/command.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "render/diff_page.h"
#include "render/diff_report.h"

namespace shatter {

namespace {

struct DiffFlags {
    std::string expected, actual, report, junit;
    DiffTolerance tolerance;
    bool no_report = false;
};

std::string default_report_dir(const std::string& actual) {
    std::filesystem::path p = std::filesystem::path(actual).lexically_normal();
    if (p.filename().empty()) p = p.parent_path();
    return p.string() + ".diff";
}

int run(const DiffFlags& f) {
    try {
        const std::string report = f.no_report ? "" : (f.report.empty() ? default_report_dir(f.actual) : f.report);
        DiffSummary s = diff_paths(f.expected, f.actual, f.tolerance, report);
        for (const ImageDiff& d : s.images) {
            if (d.failures.empty()) continue;
            std::string why;
            for (const std::string& x : d.failures) why += (why.empty() ? "" : "; ") + x;
            fmt::print("DIFFERS {}: {} (heat map: {})\n", d.name, why, d.heat_map.empty() ? "-" : d.heat_map);
        }
        double worst_rmse = 0, worst_ssim = 1;
        int worst_max = 0;
        for (const ImageDiff& d : s.images) {
            worst_rmse = std::max(worst_rmse, d.metrics.rmse);
            worst_ssim = std::min(worst_ssim, d.metrics.ssim);
            worst_max = std::max(worst_max, d.metrics.max_channel_diff);
        }
        fmt::print("diff: {} of {} images within tolerance; worst: max channel difference {}, rmse {:.4g}, ssim {:.6g}\n",
                   s.images.size() - s.failed, s.images.size(), worst_max, worst_rmse, worst_ssim);
        if (!report.empty()) {
            make_directories(report);
            const std::string json = (std::filesystem::path(report) / "summary.json").string();
            write_file_atomic(json, diff_summary_json(s));
            fmt::print("wrote: {}\n", json);
            fmt::print("wrote: {}\n", write_diff_page(s, report));
        }
        if (!f.junit.empty()) {
            write_file_atomic(f.junit, diff_junit_xml(s));
            fmt::print("wrote: {}\n", f.junit);
        }
        return s.failed ? int(ExitCode::Differs) : 0;
    } catch (const Error& e) {
        spdlog::error("{}", e.what());
        return 2;  // diff's documented code for any error
    }
}

}  // namespace

RunCommand add_diff_command(CLI::App& root) {
    auto f = std::make_shared<DiffFlags>();
    const DiffTolerance t;
    CLI::App* c = root.add_subcommand(
        "diff", "Compare two images, or two directories of frames, against tolerances. Exit 0: within tolerance; "
                "1: they differ (a heat map per failing image); 2: an error (missing frame, size mismatch, "
                "unreadable file).");
    c->add_option("expected", f->expected, "the reference image (PNG) or directory of frames")->required();
    c->add_option("actual", f->actual, "the image or directory to check")->required();
    c->add_option("--max-channel-diff", f->tolerance.max_channel_diff,
                  option_help("largest allowed difference of any channel of any pixel (255: not checked)", "levels",
                              fmt::format("{:g}", t.max_channel_diff)))
        ->check(CLI::Range(0.0, 255.0));
    c->add_option("--max-rmse", f->tolerance.max_rmse,
                  option_help("largest allowed root mean square difference", "levels", fmt::format("{:g}", t.max_rmse)))
        ->check(CLI::Range(0.0, 255.0));
    c->add_option("--min-psnr", f->tolerance.min_psnr,
                  option_help("smallest allowed PSNR (0: not checked)", "dB", fmt::format("{:g}", t.min_psnr)))
        ->check(CLI::Range(0.0, 1000.0));
    c->add_option("--min-ssim", f->tolerance.min_ssim,
                  option_help("smallest allowed SSIM of the luma", "", fmt::format("{:g}", t.min_ssim)))
        ->check(CLI::Range(-1.0, 1.0));
    c->add_option("--threshold", f->tolerance.threshold,
                  option_help("a pixel differs when one of its channels differs by more than this", "levels",
                              fmt::format("{:g}", t.threshold)))
        ->check(CLI::Range(0.0, 255.0));
    c->add_option("--max-fraction", f->tolerance.max_fraction,
                  option_help("largest allowed fraction of pixels that differ (see --threshold)", "fraction",
                              fmt::format("{:g}", t.max_fraction)))
        ->check(CLI::Range(0.0, 1.0));
    auto* report = c->add_option("--report", f->report,
                                 option_help("directory for summary.json, report.html and, per failing image, its heat map "
                                             "(NAME.heat.png) and copies of the two images", "",
                                             "ACTUAL.diff"));
    c->add_flag("--no-report", f->no_report, "write no summary, no page and no heat maps")->excludes(report);
    c->add_option("--junit", f->junit, "also write a JUnit XML report to this file (one test case per image)");
    return [f] { return run(*f); };
}

}  // namespace shatter
