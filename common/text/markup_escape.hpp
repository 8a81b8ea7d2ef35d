#pragma once
// Text placed inside HTML, SVG or XML markup: `<`, `>`, `&` and `"` as entities, so that no
// text can open an element or end an attribute.
#include <string>

namespace mcnc::text {

std::string markup_escaped(const std::string& text);

}  // namespace mcnc::text
