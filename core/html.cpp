#include "core/html.h"

#include <cstdint>

#include "core/version.h"

namespace shatter {

std::string html_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string url_path(std::string_view path) {
    static const char* const hex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : path) {
        const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                           c == '_' || c == '.' || c == '~' || c == '/';
        if (plain) {
            out += char(c);
        } else {
            out += '%';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

std::string base64(std::string_view bytes) {
    static const char* const abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
        out += abc[v >> 18];
        out += abc[(v >> 12) & 63];
        out += abc[(v >> 6) & 63];
        out += abc[v & 63];
    }
    if (i < bytes.size()) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += abc[v >> 18];
        out += abc[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? abc[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

const char* const kPageStyle = R"CSS(
:root { --fg: #1d1f23; --muted: #5b6270; --line: #d8dbe0; --bg: #ffffff; --panel: #f5f6f8; --bad: #b3261e; --ok: #1e7b34; }
* { box-sizing: border-box; }
body { margin: 0 auto; max-width: 1200px; padding: 16px 24px 40px; font: 15px/1.45 system-ui, sans-serif; color: var(--fg); background: var(--bg); }
h1 { font-size: 1.5em; margin: 0.2em 0 0.1em; }
h2 { font-size: 1.15em; margin: 1.6em 0 0.5em; padding-bottom: 0.2em; border-bottom: 1px solid var(--line); }
h3 { font-size: 1em; margin: 1.2em 0 0.4em; }
p.sub, .muted { color: var(--muted); }
p.sub { margin: 0 0 1em; }
a { color: #1a56b0; }
code, pre { font: 13px/1.4 ui-monospace, monospace; }
pre { background: var(--panel); padding: 8px 10px; overflow-x: auto; }
table { border-collapse: collapse; margin: 0.4em 0 1em; }
th, td { padding: 3px 10px 3px 0; text-align: left; vertical-align: top; border-bottom: 1px solid var(--line); }
th { font-weight: 600; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; padding-left: 10px; white-space: nowrap; }
.grid { display: grid; grid-template-columns: repeat(auto-fit, minmax(300px, 1fr)); gap: 16px; }
figure { margin: 0; }
figcaption { color: var(--muted); font-size: 0.9em; margin-top: 2px; }
img, video { max-width: 100%; height: auto; display: block; background: var(--panel); }
video { width: 100%; }
.note { background: #fff6dd; border-left: 4px solid #e0a800; padding: 8px 12px; }
.bad { color: var(--bad); font-weight: 600; }
.ok { color: var(--ok); }
.viewer { position: relative; width: 100%; aspect-ratio: 16 / 9; background: #e9ebef; }
.viewer canvas { width: 100%; height: 100%; display: block; }
.controls { display: flex; align-items: center; gap: 10px; margin: 6px 0; }
.controls input[type=range] { flex: 1; }
button { font: inherit; padding: 2px 12px; }
img.thumb { width: 160px; max-width: none; }
.grid img { width: 100%; }
.compare { position: relative; width: 100%; }
.compare img { width: 100%; image-rendering: pixelated; }
.compare img.over { position: absolute; left: 0; top: 0; }
footer { margin-top: 3em; color: var(--muted); font-size: 0.85em; }
)CSS";

std::string page_begin(const std::string& title, const std::string& subtitle_html) {
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
                      html_escape(title) + "</title>\n<style>" + kPageStyle + "</style>\n</head>\n<body>\n<h1>" +
                      html_escape(title) + "</h1>\n";
    if (!subtitle_html.empty()) out += "<p class=\"sub\">" + subtitle_html + "</p>\n";
    return out;
}

std::string page_end() { return std::string("<footer>made by shatter ") + kVersion + "</footer>\n</body>\n</html>\n"; }

}  // namespace shatter
