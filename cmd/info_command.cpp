// shatter info FILE [--json]: summarizes any stage file, or a mesh file as shatter run would take it.
#include <cstdio>

#include <fmt/format.h>

#include "cmd/command.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/stage_file.h"
#include "core/trajectory.h"
#include "core/trajectory_summary.h"
#include "prescore/mesh_check.h"
#include "prescore/model_summary.h"
#include "prescore/prescore.h"

namespace shatter {

namespace {

// A mesh file as `shatter run MESH` takes it: its size (the file's units, or the default size), its
// check in metres, whether prescore meshes it as it is or wraps it first, and whether it shows
// anything beyond its shape.
nlohmann::ordered_json mesh_summary(const std::string& path, std::string* text) {
    MeshSettings settings;
    settings.path = path;
    AutoChoices choices;
    const InputMesh input = read_input_mesh(settings, choices);
    const LoadedMesh& loaded = input.loaded;
    const bool turned = input.turned;
    const double scale = input.scale;
    const MeshCheck c = check_mesh(loaded.mesh);
    MeshCheck oriented = c;
    if (c.closed() && c.volume < 0) oriented.volume = -c.volume;
    std::string why;
    const bool as_is = meshes_as_it_is(c, oriented, true, &why);
    const Vec3 extent = c.bbox_max - c.bbox_min;
    nlohmann::ordered_json j;
    j["kind"] = "mesh";
    if (input.archive) {
        j["archive_mesh"] = input.archive->mesh_name();
        j["archive_other_meshes"] = input.archive->other_meshes();
    }
    j["vertices"] = c.vertices;
    j["triangles"] = c.triangles;
    j["closed"] = c.closed();
    j["manifold"] = c.manifold();
    j["oriented"] = c.oriented();
    j["components"] = c.components;
    j["self_intersections"] = c.self_intersections;
    j["metres_per_unit_in_file"] = loaded.metres_per_unit > 0 ? nlohmann::ordered_json(loaded.metres_per_unit) : nullptr;
    j["up"] = turned ? "z" : "y";
    j["scale_m_per_unit"] = scale;
    j["size_m"] = {extent.x(), extent.y(), extent.z()};
    j["volume_m3"] = c.volume;
    j["area_m2"] = c.area;
    j["meshed_as_it_is"] = as_is;
    if (!as_is) j["repair_why"] = why;
    j["shows_only_its_shape"] = loaded.plain;
    j["warnings"] = choices.warnings;
    const std::string size =
        loaded.metres_per_unit > 0
            ? fmt::format("{:.4g} m long, by the file's units ({:g} m per unit)", extent.maxCoeff(), scale)
            : fmt::format("{:.4g} m long: the file has no units, and shatter run makes it that long ({:.6g} m per "
                          "unit; --size or --scale sets another)", extent.maxCoeff(), scale);
    std::string archive;
    if (input.archive) {
        archive = fmt::format("archive       {} in it is read", input.archive->mesh_name());
        if (const auto& others = input.archive->other_meshes(); !others.empty())
            archive += fmt::format(" (of {} mesh files: {})", others.size() + 1, kArchiveChoice);
        archive += "\n";
    }
    *text = fmt::format("kind          mesh\n{}mesh          {}\nsize          {}\nup            {}\nmeshing       {}\n"
                        "appearance    {}\n",
                        archive, describe(c), size,
                        turned ? "the file's +z, turned to +y (" + z_up_format(input.path, input.loaded.states_z_up) + "; [mesh] up = \"y\" keeps its axes)"
                               : std::string("the file's +y ([mesh] up = \"z\" turns a z-up file to stand)"),
                        as_is ? "as it is (Mesh_3 fills it with tets)" : "alpha-wrapped first: " + why,
                        loaded.plain ? "its shape only (drawn in the material colour)"
                                     : "materials, textures or vertex colours (drawn on the pieces' outer faces)");
    for (const std::string& w : choices.warnings) *text += "warning       " + w + "\n";
    *text += fmt::format("next          shatter run {}\n", path);
    return j;
}

int run(const std::string& path, bool json) {
    const std::string bytes = read_file(path, "stage file");
    const std::string magic = stage_file_magic(bytes);
    nlohmann::ordered_json summary;
    std::string text;
    if (magic == kModelMagic) {
        summary = model_summary(decode_model(bytes, path));
        text = model_summary_text(summary);
    } else if (magic == kTrajectoryMagic) {
        summary = trajectory_summary(decode_trajectory(bytes, path));
        text = trajectory_summary_text(summary);
    } else if (!magic.empty()) {
        throw_input_error(path, "unknown stage file kind " + magic,
                          "pass a file written by shatter (a .model from prescore, a trajectory from simulate) or a mesh");
    } else {
        summary = mesh_summary(path, &text);  // not a stage file: read as a mesh (its errors say why not)
    }
    summary["file"] = path;
    if (json)
        fmt::print("{}\n", summary.dump(2));
    else
        fmt::print("file          {}\n{}", path, text);
    return 0;
}

}  // namespace

RunCommand add_info_command(CLI::App& root) {
    auto path = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    CLI::App* c = root.add_subcommand("info", "Summarize a stage file (model: pieces, tets, constraints, piece pairs, "
                                              "mass, volume, collision parts, connectivity; trajectory: frames, "
                                              "fps, duration, pieces, props, complete, settings, per-piece path "
                                              "length, top speed and final position), or a mesh file as shatter run "
                                              "takes it (its size in metres, closed, manifold, crossings, whether it is "
                                              "meshed as it is or wrapped first, its appearance).");
    c->add_option("file", *path, "the stage file or mesh file")->required();
    c->add_flag("--json", *json, "print JSON instead of text");
    return [path, json] { return run(*path, *json); };
}

}  // namespace shatter
