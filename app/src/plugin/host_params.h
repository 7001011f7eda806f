// The host's own parameters, declared once like a technique's: the values live in the App's
// ParamStore under the id "host", so `--set host.shadow_blur=4`, tours' settings, bench sweeps
// (`host.shadow_blur=0,1,2,4,8,16`) and the window's "Host" section all read and write the same
// entries (App::applyAssignments, bench_spec.h isHostKey, ui/ui.cpp).
//
// The eye-space depth-dependent blur of the shadow term and the lighting rules of seed 002
// ch. 6 (sec. 6.2, 6.3, 9.4; host_shared/eye_blur_shared.h, render/renderer.h eyeBlur*), and the
// depth pre-pass (off | on | auto: render/depth_prepass_rule.h), and screen-space contact shadows
// (issue 30; host_shared/contact_shadows_shared.h, docs/contact-shadows.md).
#pragma once

#include <cstdio>

#include "plugin/params.h"
#include "render/depth_prepass_rule.h"

namespace shadowlab {

enum HostParam : uint32_t {
    kHostShadowBlur = 0,
    kHostShadowBlurDepth = 1,
    kHostLighting = 2,
    kHostDepthPrepass = 3,
    kHostContactShadows = 4,
    kHostContactThickness = 5,
    kHostContactSteps = 6,
    kHostContactJitter = 7,
};

inline const TechniqueInfo& hostParams() {
    static const TechniqueInfo info = [] {
        TechniqueInfo t;
        t.id = "host";
        t.displayName = "Host";
        t.category = "host";
        t.explanation =
            "Passes of the host that work with any technique (seed 002 ch. 6, projection aliasing). Eye-space blur "
            "(sec. 6.3, 9.4.2): a shadow map holds depths, which cannot be blurred, so the shadow term itself is: "
            "a first pass writes the technique's term of the unlit surfaces to a screen texture, a box blur W pixels "
            "wide at the reference depth and W z_b / z beyond it (distant shadows, whose artefacts are small on "
            "screen, keep their detail) smooths it without crossing depth edges, and the main pass attenuates the "
            "light with it. Lighting (sec. 6.2, Fig. 6.7): with phong the ambient is never shadowed and the diffuse "
            "N.L darkens exactly the surfaces grazed by the light, where projection aliasing (eq. 6.1) is worst; "
            "with none the term lies on unlit surfaces and every artefact shows. Depth pre-pass: the opaque depth laid "
            "down first, so the main pass shades each visible pixel once instead of every overdrawn fragment; auto "
            "turns it on where the frame's depth complexity is high (forest) and off where it is not. Contact shadows: a "
            "short ray marched from each pixel towards the light through the camera's depth buffer finds the "
            "casters right next to the receiver, where a map's bias lifts the shadow off (peter panning); the main "
            "pass takes the minimum of it and the technique's term. It cannot see casters outside the view.";
        t.params.push_back({"shadow_blur", "Eye-space blur", ParamType::Float, 0.0, 16.0, 0.0, "px",
                            "Seed 002 sec. 6.3 / 9.4.2: the shadow term of the opaque surfaces is written to a screen "
                            "texture and blurred with a box W pixels wide at the reference depth, W z_b / z beyond it "
                            "(farther shadows less blurred), then attenuates the light. 0: off (the single main pass). "
                            "Fig. 6.6 uses 1, 2, 4, 8, 16.",
                            {}});
        // Not the near plane by default: with near 0.1 and surfaces 5-70 units away, W z_n / z is
        // under a pixel everywhere and the blur would do nothing.
        t.params.push_back({"shadow_blur_depth", "Blur reference depth", ParamType::Float, 0.0, 1e6, 10.0, "",
                            "z_b: the view depth (scene units) up to which the blur is W pixels wide, W z_b / z beyond "
                            "(0: the camera's near plane).",
                            {}});
        t.params.push_back({"lighting", "Lighting", ParamType::Enum, 0.0, 1.0, 0.0, "",
                            "Seed 002 sec. 6.2 / Fig. 6.7: phong = ambient never shadowed, diffuse (N.L) and specular "
                            "attenuated by the shadow term; none = the shadow term on unlit surfaces (no N.L, no "
                            "specular), where projection aliasing is not hidden.",
                            {"phong", "none"}});
        char autoRule[320];
        std::snprintf(autoRule, sizeof autoRule,
                      "auto: on while the opaque fragments that pass the depth test are at least %.3g per pixel, off "
                      "again at %.3g or fewer (an occlusion query read a few frames late; docs/benchmarks.md "
                      "\"Depth pre-pass\").",
                      DepthPrepassRule::kOnAbove, DepthPrepassRule::kOffBelow);
        // Labels in this order so that 0 and 1 (specs and sweeps from before `auto`) stay off and on.
        t.params.push_back({"depth_prepass", "Depth pre-pass", ParamType::Enum, 0.0, 2.0, 2.0, "",
                            std::string("A depth-only pass of the opaque surfaces, then the main pass with depth "
                                        "test EQUAL: the shadow term runs once per visible pixel, for one more "
                                        "geometry pass. ") +
                                autoRule + " 0/1 are accepted as off/on.",
                            {"off", "on", "auto"}});
        // World units, not pixels: the gap a map's bias opens at a caster's foot is a length in the
        // scene (bias times depth slope), the same at any resolution and distance; a ray in pixels
        // would cover a different part of it at every distance (docs/contact-shadows.md).
        t.params.push_back({"contact_shadows", "Contact shadows", ParamType::Float, 0.0, 100.0, 0.0, "units",
                            "Screen-space contact shadows: the length (world units) of the ray marched from each "
                            "pixel towards the light through the camera's depth; the main pass takes min(technique's "
                            "term, contact term). 0: off (the frame as without it). Forces the camera depth "
                            "pre-pass. 0.5 closes the bias gap of the test scenes.",
                            {}});
        t.params.push_back({"contact_thickness", "Contact thickness", ParamType::Float, 0.001, 100.0, 0.25, "units",
                            "How deep (world units, along the view) every surface the camera sees is assumed to be: "
                            "a ray sample at most this far behind the depth buffer is occluded. Too thin misses "
                            "casters seen edge on; too thick shadows the space behind thin casters.",
                            {}});
        t.params.push_back({"contact_steps", "Contact steps", ParamType::Int, 1.0, 64.0, 16.0, "",
                            "Samples along the contact ray (cost grows with it; a caster thinner than length / steps "
                            "can fall between two samples).",
                            {}});
        t.params.push_back({"contact_jitter", "Contact jitter", ParamType::Float, 0.0, 1.0, 1.0, "",
                            "Each pixel's samples move back by jitter x a per-pixel noise of one step (fixed over "
                            "frames): steps' banding becomes noise. 0: samples at whole steps.",
                            {}});
        return t;
    }();
    return info;
}

} // namespace shadowlab
