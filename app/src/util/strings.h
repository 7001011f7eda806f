// Small string helpers shared by error messages.
#pragma once

#include <cstdio>
#include <string>

namespace shadowlab {

// Appends `item` to a comma-separated list (written out so GCC 12's -Wrestrict false positive on
// `(cond ? "" : ", ") + s` stays away).
inline void appendListItem(std::string& list, const std::string& item) {
    if (!list.empty()) list += ", ";
    list += item;
}

// `value` with `digits` after the point ("%.*f"), for tables and pages.
inline std::string fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    return text;
}

// `text` in single quotes for a POSIX shell command line (a ' becomes '\'').
inline std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

} // namespace shadowlab
