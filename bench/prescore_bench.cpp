// prescore benchmark: the time of each phase for the bunny at several resolutions, from the
// default (~3k tets) to ~100k tets, so that the growth with tet count shows. Prints CSV to
// stdout; never fails on time. Goal (docs/benchmarks.md): the default bunny, load to written
// file, < 1 s.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/log.h"
#include "core/model_io.h"
#include "prescore/prescore.h"

using namespace shatter;

int main(int argc, char** argv) {
    setup_logging("warn");  // to standard error: standard output is the CSV
    const std::string mesh = argc > 1 ? argv[1] : "/usr/share/glmark2/models/bunny.obj";
    const std::string out = "/tmp/shatter-bench-prescore.model";
    const std::vector<double> resolutions = {10, 20, 30, 40, 60, 80};
    // prescore's phases (PrescoreReport::phase_seconds) by column; "pieces" alone when no render
    // surfaces are made. A phase not listed here goes to other_s, so that the columns add up.
    const std::vector<std::pair<std::string, std::string>> phases = {
        {"load", "load"},     {"check", "check"},         {"tetrahedralize", "tetrahedralize"},
        {"hollow", "hollow"}, {"impact", "impact"},       {"partition", "partition"},
        {"constraints", "constraints"}, {"pieces + render surfaces", "pieces_render"}, {"pieces", "pieces_render"},
        {"appearance", "appearance"}};
    const std::vector<std::string> columns = {"load", "check", "tetrahedralize", "hollow", "impact", "partition",
                                              "constraints", "pieces_render", "appearance", "other"};
    std::printf("mesh,resolution,hollow,tets,pieces,constraints,collision_parts");
    for (const std::string& c : columns) std::printf(",%s_s", c.c_str());
    std::printf(",write_s,total_s\n");
    for (bool hollow : {false, true}) {
        for (double r : resolutions) {
            MeshSettings m;
            m.path = mesh;
            m.scale = 0.1;
            PrescoreSettings s;
            s.resolution = r;
            if (hollow) s.hollow = Length{0.06, true};
            PrescoreReport report;
            auto t0 = std::chrono::steady_clock::now();
            Model model = prescore(m, s, &report);
            auto t1 = std::chrono::steady_clock::now();
            save_model(out, model);
            auto t2 = std::chrono::steady_clock::now();
            std::map<std::string, double> t;
            for (const auto& [name, sec] : report.phase_seconds) {
                const auto known = std::find_if(phases.begin(), phases.end(), [&](const auto& p) { return p.first == name; });
                t[known == phases.end() ? "other" : known->second] += sec;
            }
            size_t parts = 0;
            for (const Piece& p : model.pieces) parts += p.collision.size();
            std::printf("bunny,%g,%s,%zu,%zu,%zu,%zu", r, hollow ? "0.06" : "solid", model.mesh.tets.size(),
                        model.pieces.size(), model.constraints.size(), parts);
            for (const std::string& c : columns) std::printf(",%.4f", t[c]);
            const double write = std::chrono::duration<double>(t2 - t1).count();
            std::printf(",%.4f,%.4f\n", write, std::chrono::duration<double>(t2 - t0).count());
            std::fflush(stdout);
        }
    }
    std::remove(out.c_str());
    return 0;
}
