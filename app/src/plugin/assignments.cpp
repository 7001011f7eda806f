#include "plugin/assignments.h"

#include <algorithm>

#include "plugin/host_params.h"

namespace shadowlab {

bool applyAssignments(ParamStore& store, const std::vector<TechniqueInfo>& found, const std::vector<std::string>& assignments,
                      const std::string& technique, std::string& error) {
    const auto find = [&found](const std::string& id) -> const TechniqueInfo* {
        const auto it = std::find_if(found.begin(), found.end(), [&id](const TechniqueInfo& info) { return info.id == id; });
        return it == found.end() ? nullptr : &*it;
    };
    for (const std::string& text : assignments) {
        const auto assignment = parseAssignment(text, error);
        if (!assignment) return false;
        const std::string target = assignment->technique.empty() ? technique : assignment->technique;
        const TechniqueInfo* info = target == hostParams().id && !find(target) ? &hostParams() : find(target);
        if (!info) {
            error = "--set " + text + ": no technique '" + target + "'";
            return false;
        }
        if (!store.set(*info, assignment->param, assignment->value, error)) {
            error = "--set " + text + ": " + error;
            return false;
        }
    }
    return true;
}

} // namespace shadowlab
