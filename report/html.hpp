// The one HTML page shell of every report: a self-contained file (inline style, inline SVG, no
// network) under a Content-Security-Policy that allows no script unless the page brings its own
// under a nonce.
#pragma once

#include <string>

namespace masonry {

struct HtmlPage {
  std::string title;         // plain text (escaped here)
  std::string body;          // HTML
  std::string style;         // CSS added to the shell's own (tables, figures, body)
  std::string script_nonce;  // empty: no script may run; else scripts carrying this nonce may
  std::string head;          // HTML added to <head> (e.g. an early script under the nonce)
  int max_width_px = 1040;
};

std::string html_page(const HtmlPage& p);

// A fresh random nonce for one page's scripts: only the page's own scripts run, whatever text a
// case carries.
std::string script_nonce();

}  // namespace masonry
