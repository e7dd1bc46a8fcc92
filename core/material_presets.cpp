#include "core/material_presets.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/setting_table.h"

namespace shatter {

// One row per material. Friction is the same material sliding on itself (Bullet multiplies the
// two bodies' coefficients: against the default ground, 0.5 times this); restitution is not a
// material constant (it depends on the pair, the shape and the speed) and is an assumed value
// for every preset. docs/shot.md prints this table.
const std::vector<MaterialPreset>& material_presets() {
    static const std::vector<MaterialPreset> presets = {
        {"glass", "soda-lime glass", 70e9, 40e6, 2500, 0.9, 0.3,
         "E, tensile strength (practical, surface-flaw limited: 30 to 90 MPa), density: typical handbook values (Ashby, "
         "Materials Selection in Mechanical Design); friction: glass on glass, dry, 0.9 to 1.0 (CRC Handbook / "
         "Engineering ToolBox friction tables)"},
        {"porcelain", "hard-paste porcelain", 70e9, 40e6, 2400, 0.6, 0.3,
         "E 60 to 100 GPa, tensile strength 20 to 50 MPa, density 2,300 to 2,500: typical handbook values for "
         "porcelain (Ashby; the paper's chain, docs/scenes.md); friction: assumed, ceramic on ceramic"},
        {"ceramic_tile", "glazed ceramic tile (stoneware, ISO 13006 group BIIa)", 40e9, 15e6, 2200, 0.6, 0.3,
         "modulus of rupture >= 22 MPa required by ISO 13006 for BIIa tiles, tensile strength taken as 2/3 of it; E "
         "and bulk density: typical values for stoneware/brick and tile (Ashby class 'brick and tile'); friction: "
         "assumed"},
        {"gypsum_plaster", "set gypsum plaster (plaster of Paris)", 7e9, 1e6, 1200, 0.6, 0.1,
         "E 5 to 10 GPa, tensile strength 0.7 to 3 MPa, density 1,000 to 1,300 for set plaster: typical handbook "
         "values (Ashby; the paper's plate, docs/scenes.md); friction: assumed"},
        {"concrete", "normal-weight concrete C30/37", 33e9, 2.9e6, 2400, 0.6, 0.2,
         "E_cm 33 GPa and mean tensile strength f_ctm 2.9 MPa for C30/37: EN 1992-1-1 (Eurocode 2) Table 3.1; "
         "density 24 kN/m^3: EN 1991-1-1 Annex A; friction 0.6: EN 1992-1-1 6.2.5 (smooth interface)"},
        {"stone", "granite", 50e9, 10e6, 2650, 0.6, 0.3,
         "granite: E 40 to 70 GPa, tensile strength 7 to 25 MPa, density 2,600 to 2,700: typical rock-mechanics "
         "handbook values (Goodman, Introduction to Rock Mechanics); friction 0.6: Byerlee's rule for rock on rock "
         "(Byerlee 1978)"},
        {"ice", "freshwater polycrystalline ice, about -10 C", 9e9, 1e6, 917, 0.05, 0.2,
         "E 9 to 10 GPa, tensile strength 0.7 to 3.1 MPa: Schulson, 'The structure and mechanical behavior of ice', "
         "JOM 51(2), 1999; density 917: CRC Handbook; friction: ice on ice, 0.02 to 0.1 at sliding speeds "
         "(Schulson and Fortt 2012)"},
        {"weak_cast", "art direction: a weak, brittle cast that breaks easily (not a real material)", 2e8, 2e4, 1100,
         0.6, 0.1,
         "chosen, not measured: strength 20 kPa and density 1,100 as the demo shot (assets/bunny.toml); E 200 MPa "
         "over the demo bunny's 3.3 to 10.8 cm between piece centres (median 6.1 cm) gives 1.9e9 to 6.1e9 N/m^3, "
         "median 3.3e9, about the demo's 3e9"},
    };
    return presets;
}

const MaterialPreset* find_material_preset(const std::string& name) {
    for (const MaterialPreset& p : material_presets())
        if (name == p.name) return &p;
    return nullptr;
}

std::string material_preset_names() {
    std::string out = "\"none\"";
    for (const MaterialPreset& p : material_presets()) out += fmt::format(", \"{}\"", p.name);
    return out;
}

void apply_material_preset(const MaterialPreset& p, MaterialSettings& m) {
    m.preset = p.name;
    m.youngs_modulus = p.youngs_modulus;
    m.strength = p.tensile_strength;
    m.density = p.density;
    m.surface.friction = p.friction;
    m.surface.restitution = p.restitution;
}

std::string material_presets_markdown() {
    std::string out =
        "| preset | material | E (Pa) | tensile strength (Pa) | density (kg/m^3) | friction | restitution | source |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const MaterialPreset& p : material_presets())
        out += fmt::format("| {} | {} | {} | {} | {} | {} | {} (assumed) | {} |\n", p.name, p.material,
                           short_number(p.youngs_modulus), short_number(p.tensile_strength), short_number(p.density),
                           short_number(p.friction), short_number(p.restitution), p.source);
    return out;
}

double constraint_length(const Model& model, const Constraint& c) {
    return (model.pieces[c.piece_a].mass.center - model.pieces[c.piece_b].mass.center).norm();
}

double stiffness_number(const MaterialSettings& m) { return m.youngs_modulus ? *m.youngs_modulus : m.stiffness; }
const char* stiffness_number_key(const MaterialSettings& m) {
    return m.youngs_modulus ? "youngs_modulus" : "stiffness";
}
const char* stiffness_number_unit(const MaterialSettings& m) { return m.youngs_modulus ? "Pa" : "N/m^3"; }
void set_stiffness_number(MaterialSettings& m, double value) {
    if (m.youngs_modulus)
        m.youngs_modulus = value;
    else
        m.stiffness = value;
}

namespace {

double checked_length(const Model& model, const Constraint& c) {
    const double l = constraint_length(model, c);
    if (!(l > 0) || !std::isfinite(l))
        throw_input_error("[material] youngs_modulus",
                          fmt::format("pieces {} and {} have their centres of mass {} m apart: k = E A / l needs l > 0",
                                      c.piece_a, c.piece_b, l),
                          "give [material] stiffness (N/m^3) instead: k = stiffness x A");
    return l;
}

}  // namespace

double stiffness_factor(const MaterialSettings& m, const Model& model, const Constraint& c) {
    return m.youngs_modulus ? c.area / checked_length(model, c) : c.area;
}

ConstraintMaterial constraint_material(const MaterialSettings& m, const Model& model, const Constraint& c) {
    ConstraintMaterial out;
    // Today's rule keeps its exact arithmetic (stiffness x A), so that its bytes do not change.
    out.stiffness = m.youngs_modulus ? *m.youngs_modulus * c.area / checked_length(model, c) : m.stiffness * c.area;
    out.damping = m.damping * c.area;
    out.strength = m.strength * c.area;
    return out;
}

}  // namespace shatter
