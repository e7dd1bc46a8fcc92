#include "render/diff_page.h"

#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/html.h"

namespace shatter {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

std::string show(const json& v) {
    if (v.is_null()) return "-";
    if (v.is_number_float()) return fmt::format("{:.6g}", v.get<double>());
    if (v.is_boolean()) return v.get<bool>() ? "pass" : "FAIL";
    return v.is_string() ? v.get<std::string>() : v.dump();
}

std::string cell(const json& root, const std::string& pointer, const std::string& shown = "") {
    const json::json_pointer p(pointer);
    const json v = root.contains(p) ? root.at(p) : json(nullptr);
    return fmt::format("<td class=\"num\" data-key=\"{}\" data-value=\"{}\">{}</td>", html_escape(pointer),
                       html_escape(v.dump()), html_escape(shown.empty() ? show(v) : shown));
}

// The file names a failing image's pictures have in the report folder.
std::string stem(const ImageDiff& d) { return fs::path(d.name).stem().string(); }

// Where EXPECTED and ACTUAL of an image are: the two paths themselves, or NAME in the two folders.
std::pair<std::string, std::string> sources(const DiffSummary& s, const ImageDiff& d) {
    std::error_code ec;
    if (!fs::is_directory(s.expected, ec)) return {s.expected, s.actual};
    return {(fs::path(s.expected) / d.name).string(), (fs::path(s.actual) / d.name).string()};
}

const char* const kCompareScript = R"JS(
(function () {
  'use strict';
  document.querySelectorAll('.compare').forEach(function (box) {
    var over = box.querySelector('img.over');
    var slider = box.parentNode.querySelector('input.wipe');
    var blink = box.parentNode.querySelector('button.blink');
    var timer = null;
    function wipe() { over.style.clipPath = 'inset(0 0 0 ' + slider.value + '%)'; over.style.opacity = 1; }
    slider.addEventListener('input', function () { if (timer) { clearInterval(timer); timer = null; blink.textContent = 'Blink'; } wipe(); });
    blink.addEventListener('click', function () {
      if (timer) { clearInterval(timer); timer = null; blink.textContent = 'Blink'; wipe(); return; }
      over.style.clipPath = 'none';
      blink.textContent = 'Stop';
      timer = setInterval(function () { over.style.opacity = over.style.opacity === '0' ? 1 : 0; }, 500);
    });
    wipe();
  });
})();
)JS";

}  // namespace

std::string diff_page_html(const DiffSummary& s, const std::string& summary_json) {
    const json j = json::parse(summary_json);
    std::string out = page_begin(
        "shatter diff", fmt::format("<code>{}</code> against <code>{}</code>: {}", html_escape(s.expected), html_escape(s.actual),
                                    s.failed ? fmt::format("<span class=\"bad\">{} of {} images differ</span>", s.failed,
                                                           s.images.size())
                                             : fmt::format("<span class=\"ok\">all {} images within tolerance</span>",
                                                           s.images.size())));
    out += "<h2>Tolerances</h2>\n<table id=\"tolerance\">\n";
    const std::pair<const char*, const char*> bounds[] = {
        {"max_channel_diff", "largest channel difference (levels; 255: not checked)"},
        {"max_rmse", "largest RMSE (levels)"},
        {"min_psnr", "smallest PSNR (dB; 0: not checked)"},
        {"min_ssim", "smallest SSIM of the luma"},
        {"threshold", "a pixel differs beyond (levels)"},
        {"max_fraction", "largest fraction of differing pixels"}};
    for (const auto& [key, what] : bounds)
        out += "<tr><th>" + std::string(what) + "</th>" + cell(j, std::string("/tolerance/") + key) + "</tr>\n";
    out += "</table>\n";

    if (s.failed) out += "<h2>Failing images</h2>\n";
    for (size_t i = 0; i < s.images.size(); ++i) {
        const ImageDiff& d = s.images[i];
        if (d.failures.empty()) continue;
        const std::string n = stem(d), at = fmt::format("/results/{}/", i);
        out += fmt::format("<h3 id=\"{0}\">{0}</h3>\n<p class=\"bad\">", html_escape(d.name));
        for (size_t f = 0; f < d.failures.size(); ++f) out += (f ? "; " : "") + html_escape(d.failures[f]);
        out += "</p>\n<table class=\"metrics\"><tr><th class=\"num\">max channel diff</th><th class=\"num\">RMSE</th>"
               "<th class=\"num\">PSNR (dB)</th><th class=\"num\">SSIM</th><th class=\"num\">fraction over threshold</th></tr>\n<tr>";
        for (const char* key : {"max_channel_diff", "rmse", "psnr", "ssim", "fraction_over_threshold"}) out += cell(j, at + key);
        out += "</tr></table>\n";
        if (d.heat_map.empty()) {
            out += "<p class=\"note\">No pictures: the diff wrote no report folder.</p>\n";
            continue;
        }
        const std::string e = url_path(n + ".expected.png"), a = url_path(n + ".actual.png"),
                          h = url_path(fs::path(d.heat_map).filename().string());
        out += fmt::format("<div class=\"grid\">\n<figure><img src=\"{0}\" alt=\"expected\"><figcaption>expected</figcaption></figure>\n"
                           "<figure><img src=\"{1}\" alt=\"actual\"><figcaption>actual</figcaption></figure>\n"
                           "<figure><img src=\"{2}\" alt=\"heat map\"><figcaption>heat map: the difference over the expected "
                           "image, dark red (1 level) to white (64 and more)</figcaption></figure>\n</div>\n",
                           e, a, h);
        out += fmt::format("<div><div class=\"controls\"><input type=\"range\" class=\"wipe\" min=\"0\" max=\"100\" "
                           "value=\"50\"><span>left of the line: expected, right: actual</span><button class=\"blink\">"
                           "Blink</button></div>\n"
                           "<div class=\"compare\"><img src=\"{0}\" alt=\"expected\"><img class=\"over\" src=\"{1}\" "
                           "alt=\"actual\"></div></div>\n", e, a);
    }

    out += "<h2>Every image</h2>\n<table id=\"images\"><tr><th>image</th><th>result</th><th class=\"num\">max channel diff</th>"
           "<th class=\"num\">RMSE</th><th class=\"num\">PSNR (dB)</th><th class=\"num\">SSIM</th><th class=\"num\">fraction "
           "over threshold</th></tr>\n";
    for (size_t i = 0; i < s.images.size(); ++i) {
        const ImageDiff& d = s.images[i];
        const std::string at = fmt::format("/results/{}/", i);
        const std::string name = d.failures.empty() ? html_escape(d.name)
                                                    : fmt::format("<a href=\"#{0}\">{0}</a>", html_escape(d.name));
        out += fmt::format("<tr><td>{}</td><td class=\"{}\">{}</td>", name, d.failures.empty() ? "ok" : "bad",
                           d.failures.empty() ? "pass" : "FAIL");
        for (const char* key : {"max_channel_diff", "rmse", "psnr", "ssim", "fraction_over_threshold"})
            out += cell(j, at + key, std::string(key) == "psnr" && j.at(json::json_pointer(at + key)).is_null() ? "identical" : "");
        out += "</tr>\n";
    }
    out += "</table>\n<p><a href=\"summary.json\">summary.json</a> has the same numbers.</p>\n";
    if (s.failed) out += "<script>" + std::string(kCompareScript) + "</script>\n";
    return out + page_end();
}

std::string write_diff_page(const DiffSummary& s, const std::string& report_dir) {
    make_directories(report_dir);
    for (const ImageDiff& d : s.images) {
        if (d.failures.empty() || d.heat_map.empty()) continue;
        const auto [expected, actual] = sources(s, d);
        write_file_atomic((fs::path(report_dir) / (stem(d) + ".expected.png")).string(), read_file(expected, "expected image"));
        write_file_atomic((fs::path(report_dir) / (stem(d) + ".actual.png")).string(), read_file(actual, "actual image"));
    }
    const std::string page = (fs::path(report_dir) / "report.html").string();
    write_file_atomic(page, diff_page_html(s, diff_summary_json(s)));
    return page;
}

}  // namespace shatter
