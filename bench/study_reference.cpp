// The study's section "reference": the chain of assets/chain.toml on the continuum reference
// (bench/fem_chain.h) against quasi-static theory and against the rigid method, up to the first
// break (docs/accuracy.md section 8.2; fem_compare --scene chain runs the whole comparison), and
// the plate of assets/plate.toml (bench/fem_scene.h, 2 cells across a cube) and the rigid method
// to their first break, which the quick check compares with the free fall's first contact and
// with the committed comparison's 2-cell reference (bench/results/study/fem_plate.csv; fem_compare
// --scene plate, docs/accuracy.md section 8.3). The numbers are cheap (the chain: 2 cells across, about 650
// steps of 1e-5 s; the plate: about 70 steps of 1e-5 s and 0.33 s of the rigid plate), so quick
// and full mode run the same.
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "bench/fem_chain.h"
#include "bench/fem_scene.h"
#include "bench/study_sections.h"
#include "core/shot.h"
#include "prescore/prescore.h"

namespace shatter::study {

bool section_reference(const Options& opt, Headlines& h) {
    Csv csv(opt.out, "reference.csv",
            "method,cells,step_s,first_break_s,predicted_s,ramp_ratio,joints_broken,middle_force_ratio,cpu_s");
    // The reference: 2 cells across, h = 1e-5 s, to 0.2 ms after its first tie broke (its first
    // joint has separated by then).
    const std::clock_t c0 = std::clock();
    const fem::FemChainResult f = fem::run_fem_chain(2, 1e-5, 1e-5, 2e-4, 0.35);
    const double fem_cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    // The rigid method: the shot as shipped (its first break does not depend on alpha or the rate
    // limit, which act after it).
    const Shot shot = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/chain.toml", {"simulate.duration=0.32"});
    StudyCase c;
    c.scene = "chain";
    c.model = prescore_shot(shot, nullptr);
    c.input = SimulationInput{shot.scene, shot.object, shot.material, shot.simulate};
    const RunOutcome o = run_timed(c, 1);
    const double t0 = 0.3;  // the ends start to move
    h.chain_fem_break = f.first_separation;
    h.chain_middle_force_ratio = f.middle_force_at_break / f.middle_force_predicted;
    h.chain_predicted_break = f.predicted_break;
    h.chain_rigid_break = first_break(o.sim);
    h.chain_fem_joints = f.joints_broken.size();
    std::string joints;
    for (int j : f.joints_broken) joints += fmt::format("{}{}", joints.empty() ? "" : " ", j);
    csv.row(fmt::format("reference,2,1e-5,{},{},{},{},{},{}", fmt_double(f.first_separation),
                        fmt_double(f.predicted_break), fmt_double((f.first_separation - t0) / (f.predicted_break - t0)),
                        joints, fmt_double(h.chain_middle_force_ratio), fmt_double(fem_cpu)));
    std::string rigid_joints;
    for (const BreakRecord& b : o.sim.breaks) rigid_joints += fmt::format("{}{}", rigid_joints.empty() ? "" : " ", b.piece_a);
    csv.row(fmt::format("rigid,-,{},{},{},{},{},,{}", fmt_double(1.0 / (c.input.simulate.fps * c.input.simulate.substeps)),
                        fmt_double(h.chain_rigid_break), fmt_double(f.predicted_break),
                        fmt_double((h.chain_rigid_break - t0) / (f.predicted_break - t0)), rigid_joints,
                        fmt_double(o.cpu_seconds)));

    // The plate: the reference and the rigid method (alpha 1, as shipped) to their first break.
    const Shot plate = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/plate.toml", {"simulate.duration=0.33"});
    StudyCase p;
    p.scene = "plate";
    p.model = prescore_shot(plate, nullptr);
    p.input = SimulationInput{plate.scene, plate.object, plate.material, plate.simulate};
    fem::FemSceneSettings fs = fem::scene_settings(p.model, plate.material);
    fs.box_cells = 2;  // the committed comparison's coarser reference: a tenth of the 3-cell one's cost
    fs.after = 1e-4;
    const std::clock_t c1 = std::clock();
    const fem::FemSceneResult pf = fem::run_fem_scene(p.model, plate.scene, plate.object, fs);
    const double plate_cpu = double(std::clock() - c1) / CLOCKS_PER_SEC;
    const RunOutcome po = run_timed(p, 1);
    h.plate_contact = pf.contact_time;
    h.plate_fem_break = pf.first_break;
    h.plate_rigid_break = first_break(po.sim);
    h.plate_step = fs.h;
    // The committed comparison's 2-cell reference row (its first break; the run above takes the
    // same steps).
    std::ifstream committed(std::string(SHATTER_SOURCE_DIR) + "/bench/results/study/fem_plate.csv");
    for (std::string line; std::getline(committed, line);)
        if (line.rfind("fem 2 cells;", 0) == 0) {
            std::stringstream cells(line);
            std::string method, alpha, first;
            std::getline(cells, method, ',');
            std::getline(cells, alpha, ',');
            std::getline(cells, first, ',');
            h.plate_committed_break = std::atof(first.c_str());
        }
    csv.row(fmt::format("reference plate,{},{},{},{},,,,{}", fs.box_cells, fmt_double(fs.h), fmt_double(pf.first_break),
                        fmt_double(pf.contact_time), fmt_double(plate_cpu)));
    csv.row(fmt::format("rigid plate,-,{},{},{},,,,{}", fmt_double(1.0 / (p.input.simulate.fps * p.input.simulate.substeps)),
                        fmt_double(h.plate_rigid_break), fmt_double(pf.contact_time), fmt_double(po.cpu_seconds)));
    csv.close();
    return true;
}

}  // namespace shatter::study
