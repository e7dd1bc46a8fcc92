// The energy CSV that simulate writes (simulate/recording.cpp), read back for plots and a run's
// facts. Columns are found by name, so files of older versions (fewer columns) still read.
#pragma once

#include <string>
#include <vector>

namespace shatter {

// The series of an energy CSV of simulate (simulate/recording.cpp), columns found by name.
struct EnergySeries {
    std::vector<double> t, kinetic, potential, stored, injected;
    std::vector<double> elastic;  // empty in files of older versions
    // kinetic + potential + elastic + removed + joints_damped + contacts + integration - injected
    // - driven (constant: docs/physics.md section 5c); what the joints took (removed +
    // joints_damped: the stretch the broken ones held, and the damping); what contacts and the
    // step's integration took (contacts + integration); and driven. Empty in files of older
    // versions (integration counted as 0 where it is missing).
    std::vector<double> books, joints_took, contacts_took, driven;
    // The largest joint residual of the frame's steps (docs/physics.md section 5a); empty in files
    // of older versions.
    std::vector<double> joint_residual;
};
// Parses the CSV's text; `where` names it in errors. Throws Error(BadInput) with where:line for a
// malformed file.
EnergySeries parse_energy_csv(const std::string& text, const std::string& where);

}  // namespace shatter
