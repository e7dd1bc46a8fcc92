// Material presets ([material] preset = "NAME") and the rule that turns the [material] numbers
// into each constraint's spring and strength. The presets are declared once, one row per
// material, in core/material_presets.cpp; docs/shot.md's preset table is generated from it
// (`shatter settings-doc`, marker settings:material.presets).
//
// The rule (docs/physics.md section 2), for a constraint c of area A_c joining pieces a and b:
//   youngs_modulus E set (by a preset or the key):  k_c = E A_c / l_c,  l_c = |x_a - x_b| the
//                                                    distance between the two pieces' centres of mass
//   else (today's rule):                             k_c = stiffness A_c
//   always:                                          damping_c = damping A_c, strength_c = strength A_c
#pragma once

#include <string>
#include <vector>

#include "core/model.h"
#include "core/scene_settings.h"

namespace shatter {

struct MaterialPreset {
    const char* name;         // "glass"
    const char* material;     // what it stands for: "soda-lime glass"
    double youngs_modulus;    // (unit: Pa)
    double tensile_strength;  // (unit: Pa)
    double density;           // (unit: kg/m^3)
    double friction;          // (unit: 1) Coulomb coefficient against the same material
    double restitution;       // (unit: 1)
    const char* source;       // where the numbers come from (docs/shot.md shows it)
};

// Every preset, in the docs' order ("none" is not one: it means no preset).
const std::vector<MaterialPreset>& material_presets();
// The preset called `name`, or nullptr ("none" and unknown names).
const MaterialPreset* find_material_preset(const std::string& name);
// "\"none\", \"glass\", ...": the names [material] preset takes, for messages.
std::string material_preset_names();
// Sets youngs_modulus, strength, density, friction and restitution from the preset, and the
// preset's name.
void apply_material_preset(const MaterialPreset& p, MaterialSettings& m);
// The Markdown table of the presets with their numbers and sources (docs/shot.md).
std::string material_presets_markdown();

// A constraint's spring and breaking force under the rule above.
struct ConstraintMaterial {
    double stiffness = 0;  // k_c (unit: N/m)
    double damping = 0;    // (unit: N s/m)
    double strength = 0;   // breaking force (unit: N)
};

// l_c: the distance between the centres of mass of the two pieces the constraint joins (unit: m).
double constraint_length(const Model& model, const Constraint& c);
// k_c per unit of the material's stiffness number (youngs_modulus when set, else stiffness):
// A_c / l_c or A_c. Throws Error(BadInput) when youngs_modulus is set and l_c is not positive.
double stiffness_factor(const MaterialSettings& m, const Model& model, const Constraint& c);
// The material's stiffness number: *youngs_modulus (Pa) when set, else stiffness (N/m^3); its
// key in [material] and its unit, and setting it.
double stiffness_number(const MaterialSettings& m);
const char* stiffness_number_key(const MaterialSettings& m);   // "youngs_modulus" or "stiffness"
const char* stiffness_number_unit(const MaterialSettings& m);  // "Pa" or "N/m^3"
void set_stiffness_number(MaterialSettings& m, double value);
// k_c, damping and strength of constraint c.
ConstraintMaterial constraint_material(const MaterialSettings& m, const Model& model, const Constraint& c);

}  // namespace shatter
