// SPDX-License-Identifier: MIT
// xml_text.h — text for XML and SVG files: escaping for element text and double-quoted
// attribute values.
#pragma once

#include <string>

namespace pem::base {

// `text` with &, <, > and " replaced by their entities (' is left: attributes use ").
std::string XmlEscaped(const std::string& text);

}  // namespace pem::base
