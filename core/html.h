// What the three HTML pages share (pipeline/report_page.h for `shatter run`, pipeline/batch_page.h
// for `shatter batch`, render/diff_page.h for `shatter diff`): escaping, base64, relative links,
// one small stylesheet and the page frame. The pages are plain HTML that work from file:// with no
// network: no http(s) reference, no framework, everything they show either inline or a relative
// link to a file beside them. They are deterministic: the same inputs give the same bytes.
#pragma once

#include <string>
#include <string_view>

namespace shatter {

// Text for HTML content and attribute values: & < > " ' escaped.
std::string html_escape(std::string_view text);

// A relative URL for a path (each segment percent-encoded where it must be, '/' kept).
std::string url_path(std::string_view path);

// Standard base64 (RFC 4648, with padding), for data embedded in a page.
std::string base64(std::string_view bytes);

// The stylesheet every page carries inline.
extern const char* const kPageStyle;

// "<!DOCTYPE html>...<body>" with the title, the stylesheet and a heading; `subtitle` (HTML) below
// the heading when not empty.
std::string page_begin(const std::string& title, const std::string& subtitle_html);
// "</body></html>" and a closing line naming the program.
std::string page_end();

}  // namespace shatter
