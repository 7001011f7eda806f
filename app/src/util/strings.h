// Small string helpers shared by error messages.
#pragma once

#include <string>

namespace shadowlab {

// Appends `item` to a comma-separated list (written out so GCC 12's -Wrestrict false positive on
// `(cond ? "" : ", ") + s` stays away).
inline void appendListItem(std::string& list, const std::string& item) {
    if (!list.empty()) list += ", ";
    list += item;
}

} // namespace shadowlab
