#include "prescore/model_summary.h"

#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/stage_file.h"
#include "prescore/tet_topology.h"

namespace shatter {

nlohmann::ordered_json model_summary(const Model& m) {
    using json = nlohmann::ordered_json;
    const TetTopology topo = build_topology(m.mesh);
    double mass = 0, volume = 0;
    size_t parts = 0;
    json pieces = json::array();
    for (uint32_t i = 0; i < m.pieces.size(); ++i) {
        const Piece& p = m.pieces[i];
        std::vector<char> mask(m.mesh.tets.size(), 0);
        for (uint32_t t : p.tets) mask[t] = 1;
        int32_t components = 0;
        tet_components(topo, mask, &components);
        if (p.tets.empty()) components = p.connected ? 1 : 0;  // a generated box: one solid, no tets
        size_t fracture = 0;
        for (FaceKind k : p.surface.kinds) fracture += k == FaceKind::Fracture;
        double hull = 0;
        for (const ConvexPart& c : p.collision) hull += c.hull_volume;
        mass += p.mass.mass;
        volume += p.mass.volume;
        parts += p.collision.size();
        // What is drawn (its render surface, when it has one): its volume and volume centroid.
        json drawn_volume = nullptr, drawn_centre = nullptr;
        if (p.render) {
            double v = 0;
            Vec3 c = Vec3::Zero();
            for (const Tri& t : p.render->triangles) {
                const Vec3 &a = p.render->vertices[t[0]], &b = p.render->vertices[t[1]], &d = p.render->vertices[t[2]];
                const double six = a.dot(b.cross(d));
                v += six / 6, c += six / 24 * (a + b + d);
            }
            drawn_volume = v;
            if (v > 0) drawn_centre = {c.x() / v, c.y() / v, c.z() / v};
        }
        pieces.push_back({{"piece", i},
                          {"tets", p.tets.size()},
                          {"volume_m3", p.mass.volume},
                          {"mass_kg", p.mass.mass},
                          {"center_m", {p.mass.center.x(), p.mass.center.y(), p.mass.center.z()}},
                          {"surface_triangles", p.surface.triangles.size()},
                          {"fracture_triangles", fracture},
                          {"collision_parts", p.collision.size()},
                          {"collision_hull_volume_m3", hull},
                          {"components", components},
                          {"connected", components == 1},
                          {"render_volume_m3", drawn_volume},
                          {"render_center_m", drawn_centre}});
    }
    std::map<std::pair<uint32_t, uint32_t>, std::pair<size_t, double>> pairs;
    for (const Constraint& c : m.constraints) {
        auto& e = pairs[{c.piece_a, c.piece_b}];
        e.first += 1;
        e.second += c.area;
    }
    json pair_list = json::array();
    for (const auto& [k, v] : pairs)
        pair_list.push_back({{"pieces", {k.first, k.second}}, {"constraints", v.first}, {"area_m2", v.second}});
    bool all_connected = true;
    for (const json& p : pieces) all_connected = all_connected && p["connected"].get<bool>();
    json j;
    j["kind"] = "model";
    j["producer"] = m.producer;
    j["settings"] = json::parse(m.settings_json, nullptr, false);
    j["pieces"] = m.pieces.size();
    j["tets"] = m.mesh.tets.size();
    j["vertices"] = m.mesh.vertices.size();
    j["constraints"] = m.constraints.size();
    j["piece_pairs"] = pairs.size();
    j["density_kg_m3"] = m.density;
    j["mass_kg"] = mass;
    j["volume_m3"] = volume;
    j["collision_parts"] = parts;
    j["all_pieces_connected"] = all_connected;
    j["model_size"] = {{"bodies", m.pieces.size()},
                       {"constraints", m.constraints.size()},
                       {"collision_parts", parts},
                       {"tets", m.mesh.tets.size()}};
    size_t with_render = 0, render_triangles = 0, fell_back = 0;
    for (const Piece& p : m.pieces)
        if (p.render) ++with_render, render_triangles += p.render->triangles.size(), fell_back += p.render->fell_back;
    j["render_surfaces"] = {{"pieces", with_render}, {"triangles", render_triangles}, {"fell_back", fell_back}};
    nlohmann::ordered_json materials = nlohmann::ordered_json::array();
    for (const Material& mat : m.materials)
        materials.push_back({{"name", mat.name},
                             {"texture", mat.texture_name},
                             {"texture_type", mat.texture_mime},
                             {"texture_bytes", mat.texture.size()}});
    j["materials"] = std::move(materials);
    j["per_piece"] = std::move(pieces);
    j["per_pair"] = std::move(pair_list);
    return j;
}

std::string model_summary_text(const nlohmann::ordered_json& j) {
    std::string out;
    out += fmt::format("model         {} (density {} kg/m^3)\n", j["producer"].get<std::string>(),
                       j["density_kg_m3"].get<double>());
    out += fmt::format("model size    {} bodies, {} constraints, {} collision parts, {} tets\n",
                       j["pieces"].get<size_t>(), j["constraints"].get<size_t>(), j["collision_parts"].get<size_t>(),
                       j["tets"].get<size_t>());
    out += fmt::format("piece pairs   {} joined by constraints\n", j["piece_pairs"].get<size_t>());
    out += fmt::format("total         mass {:.6g} kg, volume {:.6g} m^3\n", j["mass_kg"].get<double>(),
                       j["volume_m3"].get<double>());
    out += fmt::format("connected     {}\n", j["all_pieces_connected"].get<bool>() ? "every piece is one component"
                                                                                  : "SOME PIECES ARE SPLIT");
    const auto& rs = j["render_surfaces"];
    if (rs["pieces"].get<size_t>() == 0)
        out += "render        the tet surfaces (no render surfaces)\n";
    else
        out += fmt::format("render        render surfaces on {} of {} pieces, {} triangles ({} on the tet surface)\n",
                           rs["pieces"].get<size_t>(), j["pieces"].get<size_t>(), rs["triangles"].get<size_t>(),
                           rs["fell_back"].get<size_t>());
    if (j.contains("materials") && !j["materials"].empty()) {
        std::string textures;
        size_t textured = 0;
        for (const auto& mat : j["materials"])
            if (mat["texture_bytes"].get<size_t>() > 0)
                textures += fmt::format("{}{} ({}, {:.0f} kB)", textured++ ? ", " : ": ", mat["texture"].get<std::string>(),
                                        mat["texture_type"].get<std::string>(), mat["texture_bytes"].get<size_t>() / 1e3);
        out += fmt::format("look          the input's: {} materials, {} textured{}\n", j["materials"].size(), textured,
                           textures);
    }
    if (j.contains("settings")) out += stage_choices_text(j["settings"]);
    out += "\npiece   tets   volume(m^3)    mass(kg)  parts  fracture-tris  connected\n";
    for (const auto& p : j["per_piece"])
        out += fmt::format("{:5} {:6} {:13.6g} {:11.6g} {:6} {:14} {:>10}\n", p["piece"].get<int>(),
                           p["tets"].get<size_t>(), p["volume_m3"].get<double>(), p["mass_kg"].get<double>(),
                           p["collision_parts"].get<size_t>(), p["fracture_triangles"].get<size_t>(),
                           p["connected"].get<bool>() ? "yes" : "NO");
    return out;
}

}  // namespace shatter
