// fem_checks: prints the continuum reference's checks against theory (bench/fem_checks.h) at
// several mesh resolutions (docs/accuracy.md, "A continuum reference"); `make study` keeps the
// tables in bench/results/study/fem_checks.md, and docs/results/study.md shows them.
//
//   fem_checks [--min-cells N] [--max-cells N] [--static-only]
//   (default: the cantilever at 1, 2, 4, 6, 8 cells across; 12 takes minutes and 0.6 GB)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench/fem_checks.h"

using namespace shatter::fem;

int main(int argc, char** argv) {
    uint32_t min_cells = 1, max_cells = 8;
    bool static_only = false;
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--min-cells" && i + 1 < argc) min_cells = uint32_t(std::atoi(argv[++i]));
        if (std::string(argv[i]) == "--max-cells" && i + 1 < argc) max_cells = uint32_t(std::atoi(argv[++i]));
        if (std::string(argv[i]) == "--static-only") static_only = true;
    }
    const CantileverGeometry g;
    std::printf("cantilever %.3g x %.3g x %.3g m, E %.3g Pa, nu %.3g, rho %.4g kg/m^3, tip load 100 N\n", g.length,
                g.side, g.side, g.material.young, g.material.poisson, g.material.density);
    std::printf("| cells across | tets | free dofs | tip deflection (um) | / Euler-Bernoulli | / Timoshenko | f1 modal (Hz) | / Euler-Bernoulli | s |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (uint32_t n : {1u, 2u, 4u, 6u, 8u, 12u, 16u}) {
        if (n > max_cells) break;
        if (n < min_cells) continue;
        const StaticResult st = cantilever_static(g, n);
        const FrequencyResult fr = static_only ? FrequencyResult{} : cantilever_frequency(g, n);
        std::printf("| %u | %zu | %zu | %.4f | %.4f | %.4f | %.2f | %.4f | %.1f |\n", n, st.tets, st.dofs,
                    1e6 * st.deflection, st.deflection / st.euler_bernoulli, st.deflection / st.timoshenko, fr.modal,
                    fr.modal / fr.euler_bernoulli, st.seconds + fr.seconds);
        std::fflush(stdout);
    }
    const StaticResult st = cantilever_static(g, 1);
    std::printf("theory: Euler-Bernoulli %.4f um, Timoshenko %.4f um; f1 Euler-Bernoulli %.2f Hz\n\n",
                1e6 * st.euler_bernoulli, 1e6 * st.timoshenko, cantilever_frequency(g, 1).euler_bernoulli);
    if (static_only) return 0;

    std::printf("first mode's shape released (tip 0.1 mm), implicit midpoint, 10 periods, no damping:\n");
    std::printf("| cells | steps / period | corotational | f1 dynamic (Hz) | / modal | / Euler-Bernoulli | energy drift | s |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (uint32_t n : {2u, 4u}) {
        for (int spp : {20, 40, 80}) {
            const FrequencyResult fr = cantilever_frequency(g, n, 10, spp, true);
            std::printf("| %u | %d | yes | %.2f | %.5f | %.4f | %.2e | %.1f |\n", n, spp, fr.dynamic, fr.dynamic / fr.modal,
                        fr.dynamic / fr.euler_bernoulli, fr.energy_drift, fr.seconds);
            std::fflush(stdout);
        }
    }

    std::printf("\nbar 0.3 x 0.01 x 0.01 m, one end pushed at 1 m/s, CG:\n");
    std::printf("| cells across | cells along | tets | steps per cell crossing | arrival (us) | c (m/s) | / sqrt(E/rho) | s |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (uint32_t n : {1u, 2u, 4u}) {
        for (double spc : {1.0, 4.0}) {
        const WaveResult w = bar_wave_speed(g.material, n, spc);
        std::printf("| %u | %u | %zu | %g | %.3f | %.1f | %.4f | %.1f |\n", n, 30 * n, w.tets, spc, 1e6 * w.arrival, w.speed,
                    w.speed / w.theory, w.seconds);
        }
        std::fflush(stdout);
    }

    std::printf("\nfree bar 0.1 x 0.02 x 0.02 m tumbling at 200 rad/s plus bending, 2 turns:\n");
    std::printf("| elasticity | steps per turn | energy drift | largest elastic energy (J) | initial energy (J) | Newton iterations (most) |\n");
    std::printf("| --- | --- | --- | --- | --- | --- |\n");
    for (bool co : {true, false})
        for (int spt : {200, 400, 800, 1600}) {
            if (!co && spt != 400) continue;
            const TumbleResult t = tumbling_bar(co, 200, 2, spt);
            std::printf("| %s | %d | %.2e | %.3e | %.4f | %.0f |\n", co ? "corotational" : "linear", spt, t.energy_drift,
                        t.max_elastic, t.initial_energy, t.max_newton);
            std::fflush(stdout);
        }

    std::printf("\ncantilever scored at x = 0.15 m (two pieces), 100 N at the tip, tensile strength 40 MPa:\n");
    std::printf("| cells across | ties | deflection scored / whole - 1 | largest tie tension (MPa) | break load (N) | beam theory (N) | ratio |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
    for (uint32_t n : {2u, 4u, 6u, 8u}) {
        if (n > max_cells) break;
        const InterfaceStaticResult r = scored_cantilever(g, n, 0.15);
        std::printf("| %u | %zu | %.1e | %.3f | %.1f | %.1f | %.4f |\n", n, r.ties,
                    r.deflection_split / r.deflection_whole - 1, 1e-6 * r.max_sigma, r.break_load, r.beam_theory,
                    r.break_load / r.beam_theory);
        std::fflush(stdout);
    }

    std::printf("\nbar 0.1 x 0.01 x 0.01 m scored at mid-length, clamped, far end pulled at 1 cm/s, h = 10 us:\n");
    std::printf("| cells across | ties | first break (ms) | strength L / (E v) (ms) | ratio | broken | fragments | tension spread before | s |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (uint32_t n : {1u, 2u, 4u}) {
        const TensionBreakResult r = bar_tension_break(n);
        std::printf("| %u | %zu | %.4f | %.4f | %.4f | %zu | %zu | %.2e | %.1f |\n", n, r.ties, 1e3 * r.break_time,
                    1e3 * r.predicted, r.break_time / r.predicted, r.broken, r.fragments, r.sigma_spread, r.seconds);
        std::fflush(stdout);
    }
    return 0;
}
