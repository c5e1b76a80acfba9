// Well-formedness of XML (SVG figures, drawings) by expat, an XML parser independent of the
// writers: what a browser or an XML tool will make of the file.
#pragma once

#include <expat.h>

#include <string>

namespace masonry::test {

// True when `text` is a well-formed XML document; otherwise `why` holds expat's reason and line.
inline bool xml_well_formed(const std::string& text, std::string& why) {
  XML_Parser p = XML_ParserCreate(nullptr);
  const bool ok = XML_Parse(p, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_OK;
  if (!ok)
    why = std::string(XML_ErrorString(XML_GetErrorCode(p))) + " at line " + std::to_string(XML_GetCurrentLineNumber(p)) + ", column " +
          std::to_string(XML_GetCurrentColumnNumber(p));
  XML_ParserFree(p);
  return ok;
}

}  // namespace masonry::test
