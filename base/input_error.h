// SPDX-License-Identifier: MIT
// input_error.h — the one exception type for bad user input (case files, output paths).
// Convention: what() is a single line `<path>: <cause>`, where cause names the offending key
// inside the file (e.g. `passes[2].vertices[7]: NaN`), so a CLI can print it prefixed by its name.
// Not for internal invariant violations (those are bugs, not input errors).
#pragma once

#include <stdexcept>
#include <string>

namespace pem::base {

class InputError : public std::runtime_error {
  public:
    InputError(const std::string& path, const std::string& cause)
        : std::runtime_error(OneLine(path + ": " + cause)) {}

  private:
    // Line breaks (e.g. inside a JSON parser's message) become spaces: what() is one line.
    static std::string OneLine(std::string text) {
        for (char& c : text)
            if (c == '\n' || c == '\r') c = ' ';
        return text;
    }
};

}  // namespace pem::base
