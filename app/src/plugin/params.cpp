// Parameter descriptors and values (see params.h).
#include "plugin/params.h"

#include <cstddef>

#include "util/strings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace shadowlab {
namespace {

std::vector<std::string> splitLabels(const char* labels) {
    std::vector<std::string> out;
    if (!labels) return out;
    std::string current;
    for (const char* c = labels; *c; ++c) {
        if (*c == '|') {
            out.push_back(current);
            current.clear();
        } else {
            current += *c;
        }
    }
    out.push_back(current);
    return out;
}

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

std::optional<double> parseNumber(const std::string& text) {
    double value = 0.0;
    const char* begin = text.data();
    const char* end = begin + text.size();
    const auto result = std::from_chars(begin, end, value);
    if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

std::string rangeText(const ParamSpec& spec) {
    std::string text = "[";
    text += formatParamValue(spec, spec.minValue);
    text += ", ";
    text += formatParamValue(spec, spec.maxValue);
    text += "]";
    return text;
}

} // namespace

const ParamSpec* TechniqueInfo::findParam(const std::string& paramId) const {
    const int index = paramIndex(paramId);
    return index < 0 ? nullptr : &params[size_t(index)];
}

int TechniqueInfo::paramIndex(const std::string& paramId) const {
    for (size_t i = 0; i < params.size(); ++i)
        if (params[i].id == paramId) return int(i);
    return -1;
}

uint32_t TechniqueInfo::flagsFor(const std::vector<double>& values) const {
    uint32_t result = flags;
    for (const FlagRule& rule : flagRules) {
        const bool holds = rule.param >= 0 && size_t(rule.param) < values.size() &&
                           std::find(rule.values.begin(), rule.values.end(), values[size_t(rule.param)]) != rule.values.end();
        if (!holds) result &= ~rule.flags;
    }
    return result;
}

TechniqueInfo copyDescriptor(const TechniqueDesc& desc, const std::filesystem::path& library) {
    auto text = [](const char* s) { return std::string(s ? s : ""); };
    TechniqueInfo info;
    // Fields beyond the plugin's structSize do not exist in its descriptor: defaults then.
    auto has = [&](size_t offset, size_t size) { return desc.structSize >= offset + size; };
    info.descriptorSize = desc.structSize;
    if (!has(offsetof(TechniqueDesc, paramCount), sizeof(desc.paramCount))) return info;
    info.id = text(desc.id);
    info.displayName = text(desc.displayName);
    info.category = text(desc.category);
    info.explanation = text(desc.explanation);
    info.shadowGlsl = text(desc.shadowGlsl);
    info.library = library;
    info.flags = has(offsetof(TechniqueDesc, flags), sizeof(desc.flags)) ? desc.flags : 0u;
    if (has(offsetof(TechniqueDesc, translucencyModel), sizeof(desc.translucencyModel)))
        info.translucencyModel = desc.translucencyModel;
    for (uint32_t i = 0; i < desc.paramCount && desc.params; ++i) {
        const ParamDesc& p = desc.params[i];
        info.params.push_back({text(p.id), text(p.label), p.type, p.minValue, p.maxValue, p.defaultValue,
                               text(p.unit), text(p.help), splitLabels(p.type == ParamType::Enum ? p.enumLabels : nullptr)});
    }
    if (has(offsetof(TechniqueDesc, debugViews), sizeof(desc.debugViews)) && desc.debugViews) {
        if (*desc.debugViews) info.debugViews = splitLabels(desc.debugViews);   // "": none
        info.debugViewsDeclared = true;
    }
    // Conditions were checked by validateDescriptor; one that still does not resolve is dropped.
    if (has(offsetof(TechniqueDesc, flagConditionCount), sizeof(desc.flagConditionCount)) && desc.flagConditions)
        for (uint32_t i = 0; i < desc.flagConditionCount; ++i) {
            const FlagCondition& c = desc.flagConditions[i];
            TechniqueInfo::FlagRule rule;
            rule.flags = c.flags & info.flags;
            rule.param = info.paramIndex(text(c.param));
            if (rule.param < 0 || !rule.flags) continue;
            for (const std::string& value : splitLabels(c.values)) {
                std::string ignored;
                if (auto v = parseParamValue(info.params[size_t(rule.param)], value, ignored)) rule.values.push_back(*v);
            }
            info.flagRules.push_back(std::move(rule));
        }
    return info;
}

std::optional<double> parseParamValue(const ParamSpec& spec, const std::string& text, std::string& error) {
    std::optional<double> value;
    switch (spec.type) {
    case ParamType::Bool: {
        const std::string t = lower(text);
        if (t == "true" || t == "on" || t == "1" || t == "yes") value = 1.0;
        else if (t == "false" || t == "off" || t == "0" || t == "no") value = 0.0;
        else {
            error = "parameter '" + spec.id + "': '" + text + "' is not a boolean (use true/false, on/off, 1/0)";
            return std::nullopt;
        }
        return value;
    }
    case ParamType::Enum: {
        for (size_t i = 0; i < spec.enumLabels.size(); ++i)
            if (lower(spec.enumLabels[i]) == lower(text)) return double(i);
        value = parseNumber(text);
        if (!value || *value != std::floor(*value) || *value < 0 || *value >= double(spec.enumLabels.size())) {
            std::string labels;
            for (const auto& label : spec.enumLabels) appendListItem(labels, label);
            error = "parameter '" + spec.id + "': '" + text + "' is not one of " + labels;
            return std::nullopt;
        }
        return value;
    }
    case ParamType::Int:
    case ParamType::Float:
        value = parseNumber(text);
        if (!value) {
            error = "parameter '" + spec.id + "': '" + text + "' is not a number";
            return std::nullopt;
        }
        if (spec.type == ParamType::Int && *value != std::floor(*value)) {
            error = "parameter '" + spec.id + "': '" + text + "' is not an integer";
            return std::nullopt;
        }
        if (*value < spec.minValue || *value > spec.maxValue) {
            error = "parameter '" + spec.id + "': " + text + " is out of range " + rangeText(spec);
            return std::nullopt;
        }
        return value;
    }
    return std::nullopt;
}

std::string formatParamValue(const ParamSpec& spec, double value) {
    switch (spec.type) {
    case ParamType::Bool: return value != 0.0 ? "true" : "false";
    case ParamType::Enum: {
        const auto index = size_t(std::max(0.0, value));
        return index < spec.enumLabels.size() ? spec.enumLabels[index] : std::to_string(index);
    }
    case ParamType::Int: return std::to_string(static_cast<long long>(std::llround(value)));
    case ParamType::Float: {
        std::ostringstream out;
        out << value;
        return out.str();
    }
    }
    return "";
}

std::optional<ParamAssignment> parseAssignment(const std::string& text, std::string& error) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
        error = "--set '" + text + "': expected key=value";
        return std::nullopt;
    }
    ParamAssignment assignment;
    std::string key = text.substr(0, equals);
    assignment.value = text.substr(equals + 1);
    if (const auto dot = key.find('.'); dot != std::string::npos) {
        assignment.technique = key.substr(0, dot);
        key = key.substr(dot + 1);
    }
    assignment.param = key;
    return assignment;
}

std::vector<double>& ParamStore::values(const TechniqueInfo& info) {
    auto [it, inserted] = values_.try_emplace(info.id);
    if (inserted || it->second.size() != info.params.size()) {
        it->second.clear();
        for (const ParamSpec& p : info.params) it->second.push_back(p.defaultValue);
    }
    return it->second;
}

bool ParamStore::set(const TechniqueInfo& info, const std::string& paramId, const std::string& valueText,
                     std::string& error) {
    const int index = info.paramIndex(paramId);
    if (index < 0) {
        std::string known;
        for (const auto& p : info.params) appendListItem(known, p.id);
        error = "technique '" + info.id + "' has no parameter '" + paramId + "'" +
                (known.empty() ? " (it has none)" : " (known: " + known + ")");
        return false;
    }
    const auto value = parseParamValue(info.params[size_t(index)], valueText, error);
    if (!value) return false;
    values(info)[size_t(index)] = *value;
    return true;
}

void ParamStore::resetToDefaults(const TechniqueInfo& info) {
    auto& v = values(info);
    for (size_t i = 0; i < info.params.size(); ++i) v[i] = info.params[i].defaultValue;
}

void ParamStore::remap(const TechniqueInfo& before, const TechniqueInfo& after) {
    const std::vector<double> old = values(before);
    std::vector<double> fresh;
    for (const ParamSpec& p : after.params) {
        const int oldIndex = before.paramIndex(p.id);
        double v = oldIndex >= 0 ? old[size_t(oldIndex)] : p.defaultValue;
        fresh.push_back(std::clamp(v, p.minValue, p.maxValue));
    }
    values_[after.id] = std::move(fresh);
}

} // namespace shadowlab
