// "--set" assignments applied to a store of parameter values: the one rule for every command
// (App::applyAssignments), also used on a store of its own to check a command line against the
// techniques' descriptors before a GL context exists (cli/common.cpp).
#pragma once

#include <string>
#include <vector>

#include "plugin/params.h"

namespace shadowlab {

// A bare key goes to `technique`, "t.param" to technique t, "host.param" to the host's own
// parameters (plugin/host_params.h) unless a technique is named "host". `found`: the techniques
// ids are looked up in. Stops at the first error, which names the assignment.
bool applyAssignments(ParamStore& store, const std::vector<TechniqueInfo>& found, const std::vector<std::string>& assignments,
                      const std::string& technique, std::string& error);

} // namespace shadowlab
