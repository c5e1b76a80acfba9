#include "report/html.hpp"

#include <cstdio>
#include <random>

#include "report/escape.hpp"

namespace masonry {

std::string script_nonce() {
  std::random_device rd;
  char b[40];
  std::snprintf(b, sizeof b, "%08x%08x%08x", rd(), rd(), rd());
  return b;
}

std::string html_page(const HtmlPage& p) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'";
  if (!p.script_nonce.empty()) o += "; script-src 'nonce-" + p.script_nonce + "'";
  o += "\">\n<title>" + xml_escape(p.title) + "</title>\n" + p.head;
  o += "<style>\nbody{font-family:Helvetica,Arial,sans-serif;max-width:" + std::to_string(p.max_width_px) +
       "px;margin:1em auto;padding:0 1em;color:#222}\n"
       "table{border-collapse:collapse;margin:0.5em 0;font-size:14px}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
       ".l{text-align:left}th{background:#f3f3f3}\nsvg{max-width:100%;height:auto}\n";
  o += p.style;
  o += "</style>\n</head>\n<body>\n" + p.body + "</body>\n</html>\n";
  return o;
}

}  // namespace masonry
