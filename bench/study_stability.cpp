// The stability map (docs/accuracy.md section 6): the rig (a fixed bar and two bars in a row,
// 8 constraints) over step size and stiffness, mass ratio and alpha, alpha and rate limit, each
// run classified as refused / NaN / energy growth / cascade / fly-apart / stable; then the 3D
// scenes (bench/study_stability_scenes.h) up to mass ratio 1,000, each method with iterative and
// with direct joints, classified the same way and held to their physical meaning of stable.
#include <chrono>
#include <cstdio>
#include <map>

#include <spdlog/spdlog.h>

#include "bench/study_sections.h"
#include "bench/study_stability_scenes.h"

namespace shatter::study {

namespace {

std::string d(double v) { return fmt_double(v); }

struct Cell {
    Stability cls = Stability::Stable;
    bool guard_refuses = false;  // the CFM guard (max_cfm 0.5) refuses these settings
    size_t breaks = 0;
    double growth = 0, wall = 0;
    double injected = 0, momentum_work = 0;  // summed over the breaks (pair frames; dP . V on top)
};

// Runs with the CFM guard; when it refuses, runs again without it (max_cfm 0.99) to see what
// the guard prevents.
Cell run_cell(StudyCase c) {
    Cell cell;
    c.input.simulate.max_cfm = 0.5;
    RunOutcome o = run_case(c);
    if (o.refused) {
        cell.guard_refuses = true;
        c.input.simulate.max_cfm = 0.99;
        o = run_case(c);
    }
    cell.cls = classify(c, o, &cell.growth);
    cell.breaks = o.sim.breaks.size();
    for (const BreakRecord& b : o.sim.breaks) cell.injected += b.injected_energy, cell.momentum_work += b.momentum_work;
    cell.wall = o.wall_seconds;
    return cell;
}

void row(Csv& csv, const std::string& map, const std::string& method, const char* xn, double x, const char* yn,
         double y, const Cell& c) {
    csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}", map, method, xn, d(x), yn, d(y), to_string(c.cls),
                        c.guard_refuses, c.breaks, d(c.growth), d(c.wall), d(c.injected), d(c.momentum_work)));
}

// A method's name, optionally with "+direct" for [simulate] joints = "direct" or "+auto" for the
// shipped "auto" (direct); without either the joints are iterative.
void apply_method_and_joints(const std::string& name, SimulationInput& in) {
    const size_t plus = name.find('+');
    apply_method(name.substr(0, plus), in);
    const std::string joints = plus == std::string::npos ? "" : name.substr(plus + 1);
    in.simulate.joints = joints == "direct" ? JointSolve::Direct
                         : joints == "auto" ? JointSolve::Auto
                                            : JointSolve::Iterative;
}

// The 3D scenes: every scene x {plain, energized, opposed} x {iterative, direct}, the hanging
// chains and the stacks at mass ratios 1 to 1,000, into stability_scenes.csv and a table on
// stdout. The quick study leaves out the grid.
void scenes_3d(const Options& opt) {
    Csv csv(opt.out, "stability_scenes.csv",
            "scene,method,joints,mass_ratio,class,guard_refuses,physical,stable,breaks,far_breaks,measure,open_m,"
            "ke_end_J,ke_peak_J,top_speed_m_s,wall_s");
    std::string table = fmt::format("{:<8} {:>5} {:<10} {:<9} {:<14} {:>6} {:>4} {:>10} {:>9} {:>9}  {}\n", "scene",
                                    "ratio", "method", "joints", "class", "breaks", "far", "measure", "KE end J",
                                    "KE peak J", "stable");
    for (const std::string& scene : scenes3d::names()) {
        if (scene == "grid" && opt.quick) continue;  // ~75 s
        const bool ratios = scene == "hanging" || scene == "alternating" || scene.rfind("stack", 0) == 0;
        for (double ratio : ratios ? std::vector<double>{1, 10, 100, 1000} : std::vector<double>{1})
            for (const char* m : {"plain", "energized", "opposed"})
                for (const char* joints : {"", "+direct"}) {
                    StudyCase c = scenes3d::make_scene(scene, ratio);
                    apply_method_and_joints(std::string(m) + joints, c.input);
                    const auto t0 = std::chrono::steady_clock::now();
                    const scenes3d::Verdict v = scenes3d::run_and_judge(c);
                    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                    const char* jn = *joints ? "direct" : "iterative";
                    csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", scene, m, jn, d(ratio),
                                        to_string(v.cls), v.guard_refuses, v.physical, v.stable(), v.breaks,
                                        v.far_breaks, d(v.measure), d(v.open), d(v.ke_end), d(v.ke_peak),
                                        d(v.top_speed), d(wall)));
                    const std::string cls = std::string(v.guard_refuses ? "(refused) " : "") + to_string(v.cls);
                    table += fmt::format("{:<8} {:>5} {:<10} {:<9} {:<14} {:>6} {:>4} {:>10.3g} {:>9.2g} {:>9.2g}  {}\n",
                                         scene, ratio, m, jn, cls, v.breaks, v.far_breaks, v.measure, v.ke_end,
                                         v.ke_peak, v.stable() ? "yes" : "no");
                }
    }
    csv.close();
    std::printf("stability, 3D scenes (measure: hanging, alternating sag / expected - 1; stack top displacement m; "
                "tower far boxes' top speed m/s; grid largest displacement m. ratio: block / link, top / bottom box)"
                "\n%s", table.c_str());
    std::fflush(stdout);
}

}  // namespace

bool section_stability(const Options& opt, Headlines& h) {
    Csv csv(opt.out, "stability.csv", "map,method,x_name,x,y_name,y,class,guard_refuses,breaks,energy_growth_J,wall_s,injected_J,"
            "momentum_work_J");
    const bool q = false;  // the rig is cheap: the quick study draws the full maps too
    // Map 1: step size x stiffness, every method.
    const std::vector<uint32_t> substeps = q ? std::vector<uint32_t>{2, 8, 32} : std::vector<uint32_t>{1, 2, 4, 8, 16, 32, 64};
    const std::vector<double> stiffness =
        q ? std::vector<double>{1e9, 1e11, 1e13} : std::vector<double>{1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14};
    std::vector<std::string> ms;
    for (const Method& m : methods())
        if (!q || std::string(m.name) == "plain" || std::string(m.name) == "energized") ms.push_back(m.name);
    spdlog::info("study: stability map h x stiffness");
    for (const std::string& m : ms)
        for (uint32_t s : substeps)
            for (double k : stiffness) {
                RigSettings r;
                r.substeps = s;
                r.stiffness = k;
                StudyCase c = rig_case(r);
                apply_method(m, c.input);
                const Cell cell = run_cell(c);
                row(csv, "step_stiffness", m, "h_s", 1.0 / (r.fps * s), "stiffness_N_m3", k, cell);
                if (!cell.guard_refuses && m == "plain") h.cells_plain++, h.stable_plain += cell.cls == Stability::Stable;
                if (!cell.guard_refuses && m == "energized")
                    h.cells_energized++, h.stable_energized += cell.cls == Stability::Stable;
            }
    // Map 2: mass ratio x alpha.
    const std::vector<double> ratios = q ? std::vector<double>{0.01, 1, 100} : std::vector<double>{1e-3, 1e-2, 0.1, 1, 10, 100, 1e3};
    const std::vector<double> alphas = q ? std::vector<double>{0, 1, 10} : std::vector<double>{0, 0.5, 1, 2, 5, 10, 100};
    // "+direct": the method with [simulate] joints = "direct" (simulate/bullet_solver.h).
    // "opposed+auto": the shipped method with the shipped joints (plain at alpha 0).
    std::vector<std::string> ms2 = q ? std::vector<std::string>{"energized", "energized+direct", "opposed+auto"}
                                     : std::vector<std::string>{"energized", "energized+direct", "opposed+auto",
                                                                "paper", "opposed", "rate_limit", "rollback"};
    spdlog::info("study: stability map mass ratio x alpha");
    std::map<std::pair<std::string, std::pair<double, double>>, Stability> cls;
    for (const std::string& m : ms2)
        for (double ratio : ratios)
            for (double a : alphas) {
                RigSettings r;
                r.mass_ratio = ratio;
                r.alpha = a;
                StudyCase c = rig_case(r);
                apply_method_and_joints(m, c.input);
                c.input.material.alpha = a;
                const Cell cell = run_cell(c);
                cls[{m, {ratio, a}}] = cell.cls;
                row(csv, "mass_alpha", m, "mass_ratio", ratio, "alpha", a, cell);
            }
    for (double ratio : ratios)
        for (double a : alphas)
            if (a <= 10) {
                h.shipped_cells++;
                h.shipped_stable += cls[{"opposed+auto", {ratio, a}}] == Stability::Stable;
            }
    for (double ratio : ratios)
        for (double a : alphas)
            if (ratio >= 100 && a <= 10) {
                h.direct_cells_heavy++;
                h.direct_stable_heavy += cls[{"energized+direct", {ratio, a}}] == Stability::Stable;
            }
    // Plain breaking is energized at alpha = 0 (the map's first row).
    for (const std::string& m : ms2) h.stable_where_plain.push_back({m, 0});
    for (double ratio : ratios)
        for (double a : alphas) {
            if (a == 0 || cls[{"energized", {ratio, 0.0}}] != Stability::Stable) continue;
            h.plain_stable_cells++;
            for (auto& [m, n] : h.stable_where_plain) n += cls[{m, {ratio, a}}] == Stability::Stable;
        }
    // Map 3: alpha x rate limit (energized).
    if (!q) {
        spdlog::info("study: stability map alpha x rate limit");
        for (double rate : {0.0, 0.01, 0.03, 0.1, 0.3})
            for (double a : alphas) {
                RigSettings r;
                r.alpha = a;
                StudyCase c = rig_case(r);
                apply_method("energized", c.input);
                c.input.material.alpha = a;
                c.input.simulate.rate_limit = rate;
                row(csv, "alpha_rate", "energized", "alpha", a, "rate_limit_s", rate, run_cell(c));
            }
    }
    csv.close();
    spdlog::info("study: stability 3D scenes");
    scenes_3d(opt);
    return true;
}

}  // namespace shatter::study
