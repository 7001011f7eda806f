// Small string helpers shared by error messages.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

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

// `value` in messages: `precision` significant digits, as "%g" writes them (1e+09, 0.25, inf).
inline std::string formatNumber(double value, int precision = 6) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.*g", precision, value);
    return text;
}

// `text` in single quotes for a POSIX shell command line (a ' becomes '\'').
inline std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// "a,b,c" into its items, for every comma-separated value of the command line (--techniques,
// --sweep's values, --budget, ...): an empty item ("512,,1024", a comma at either end, or nothing
// at all) is an error naming `option`, never skipped, since skipping makes "" mean "all".
inline bool splitList(const std::string& text, const std::string& option, std::vector<std::string>& items,
                      std::string& error) {
    items.clear();
    size_t start = 0;
    for (;;) {
        const size_t comma = text.find(',', start);
        const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (item.empty()) {
            error = option + " '" + text + "': item " + std::to_string(items.size() + 1) +
                    " of the list is empty (separate the values by single commas, nothing before the first or after the last)";
            return false;
        }
        items.push_back(item);
        if (comma == std::string::npos) return true;
        start = comma + 1;
    }
}

// `text` with its control bytes written as \xNN (a NUL, a carriage return or an escape sequence
// from a file would otherwise cut or garble the message that quotes it); newlines and tabs stay
// when `keepLayout`.
inline std::string printable(const std::string& text, bool keepLayout = false) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if ((byte < 0x20 && !(keepLayout && (c == '\n' || c == '\t'))) || byte == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof(hex), "\\x%02x", byte);
            out += hex;
        } else {
            out += c;
        }
    }
    return out;
}

// A value from a file or the command line inside a message: in double quotes, printable, and at
// most `maxBytes` of it (a 16 MiB key must not become a 16 MiB message).
inline std::string quoteForMessage(const std::string& text, size_t maxBytes = 80) {
    const bool cut = text.size() > maxBytes;
    return "\"" + printable(cut ? text.substr(0, maxBytes) : text) + (cut ? "...\"" : "\"");
}

} // namespace shadowlab
