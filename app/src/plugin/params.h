// Technique descriptors copied out of the plugin library (so they outlive a hot-reload unload),
// and the host's store of parameter values: the one place the GUI, --set, sweeps and hot reload
// read and write them.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "shadowlab/technique.h"

namespace shadowlab {

struct ParamSpec {
    std::string id;
    std::string label;
    ParamType type = ParamType::Float;
    double minValue = 0.0;
    double maxValue = 1.0;
    double defaultValue = 0.0;
    std::string unit;
    std::string help;
    std::vector<std::string> enumLabels;
};

struct TechniqueInfo {
    std::string id;
    std::string displayName;
    std::string category;
    std::string explanation;
    std::string shadowGlsl;
    std::vector<ParamSpec> params;
    uint32_t flags = 0;               // TechniqueFlag bits
    TranslucencyModel translucencyModel = TranslucencyModel::Opaque; // Opaque unless the descriptor covers it
    uint32_t descriptorSize = sizeof(TechniqueDesc);
    // TechniqueDesc::debugViews split at '|' (declared: the descriptor has the field and set it).
    std::vector<std::string> debugViews;
    bool debugViewsDeclared = false;
    std::filesystem::path library;    // the .so it came from (empty for host-provided entries)
    // The descriptor's flagConditions, resolved: `flags` hold only while parameter `param` has
    // one of `values`.
    struct FlagRule {
        uint32_t flags = 0;
        int param = -1;
        std::vector<double> values;
    };
    std::vector<FlagRule> flagRules;

    // The flags that hold for these parameter values (descriptor order): `flags` less those of
    // every rule whose parameter has none of its values.
    uint32_t flagsFor(const std::vector<double>& values) const;

    const ParamSpec* findParam(const std::string& paramId) const;
    int paramIndex(const std::string& paramId) const;
};

// Copies a descriptor the host has validated (validateDescriptor in plugin_library.h).
TechniqueInfo copyDescriptor(const TechniqueDesc& desc, const std::filesystem::path& library);

// Parses `text` for `spec`: numbers for Float/Int (Int must be integral), true/false/on/off/1/0
// for Bool, a label or an index for Enum. Range is checked. Errors name the parameter.
std::optional<double> parseParamValue(const ParamSpec& spec, const std::string& text, std::string& error);
std::string formatParamValue(const ParamSpec& spec, double value);

// "--set key=value": key is "param" (the technique in use) or "technique.param".
struct ParamAssignment {
    std::string technique;   // empty: the technique in use
    std::string param;
    std::string value;
};
std::optional<ParamAssignment> parseAssignment(const std::string& text, std::string& error);

class ParamStore {
public:
    // Values of `info`'s parameters in descriptor order; defaults on first use.
    std::vector<double>& values(const TechniqueInfo& info);
    // Sets one parameter from text; on error the stored value is unchanged.
    bool set(const TechniqueInfo& info, const std::string& paramId, const std::string& valueText, std::string& error);
    void resetToDefaults(const TechniqueInfo& info);
    // After a hot reload: keep values by parameter id, defaults for new ids, clamp to new ranges.
    void remap(const TechniqueInfo& before, const TechniqueInfo& after);

private:
    std::map<std::string, std::vector<double>> values_;
};

} // namespace shadowlab
