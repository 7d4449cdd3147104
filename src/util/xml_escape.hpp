// Text as it may stand in XML (and SVG) content and attribute values.
#pragma once

#include <string>

namespace wp {

// `text` with &, <, >, " and ' written as entities.
std::string xml_escape(const std::string& text);

} // namespace wp
