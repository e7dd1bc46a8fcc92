#include "core/model_io.h"

#include <cmath>

#include "core/atomic_file.h"
#include "core/binary_io.h"
#include "core/stage_file.h"

namespace shatter {

namespace {

void put_surface(ByteWriter& w, const PieceSurface& s) {
    w.u32(static_cast<uint32_t>(s.vertices.size()));
    for (const Vec3& v : s.vertices) w.vec3(v);
    w.u32(static_cast<uint32_t>(s.triangles.size()));
    for (size_t i = 0; i < s.triangles.size(); ++i) {
        for (uint32_t v : s.triangles[i]) w.u32(v);
        w.u8(static_cast<uint8_t>(s.kinds[i]));
    }
}

PieceSurface get_surface(ByteReader& r) {
    PieceSurface s;
    s.vertices.resize(r.count(24, "surface vertices"));
    for (Vec3& v : s.vertices) v = r.finite_vec3("a surface vertex");
    const uint32_t n = r.count(13, "surface triangles");
    s.triangles.resize(n);
    s.kinds.resize(n);
    const uint32_t nv = static_cast<uint32_t>(s.vertices.size());
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t& v : s.triangles[i]) v = r.index(nv, "surface vertex index");
        uint8_t kind = r.u8();
        if (kind > static_cast<uint8_t>(FaceKind::Cavity)) r.fail("unknown face kind " + std::to_string(kind));
        s.kinds[i] = static_cast<FaceKind>(kind);
    }
    return s;
}

// Version 2: after `connected`, u8 1 and the render surface, or u8 0 (docs/formats.md).
void put_render_surface(ByteWriter& w, const std::optional<RenderSurface>& rs) {
    w.u8(rs ? 1 : 0);
    if (!rs) return;
    w.u32(static_cast<uint32_t>(rs->vertices.size()));
    for (size_t i = 0; i < rs->vertices.size(); ++i) {
        w.vec3(rs->vertices[i]);
        w.vec3(rs->normals[i]);
    }
    w.u32(static_cast<uint32_t>(rs->triangles.size()));
    for (size_t i = 0; i < rs->triangles.size(); ++i) {
        for (uint32_t v : rs->triangles[i]) w.u32(v);
        w.u8(static_cast<uint8_t>(rs->kinds[i]));
    }
    w.u8(rs->fell_back ? 1 : 0);
}

// Version 3: after the render surface's fell_back byte, a u8 of flags (1: uv, 2: colour, 4:
// material) and the arrays they announce (docs/formats.md).
void put_appearance(ByteWriter& w, const RenderSurface& rs) {
    w.u8(uint8_t((rs.uv.empty() ? 0 : 1) | (rs.colour.empty() ? 0 : 2) | (rs.material.empty() ? 0 : 4)));
    for (const auto& uv : rs.uv) w.f32(uv[0]), w.f32(uv[1]);
    for (const auto& c : rs.colour)
        for (float x : c) w.f32(x);
    for (uint32_t m : rs.material) w.u32(m);
}

void get_appearance(ByteReader& r, RenderSurface& s) {
    const uint8_t flags = r.u8();
    if (flags > 7) r.fail("render surface appearance flags " + std::to_string(flags) + " (0 to 7)");
    auto finite = [&](const char* what) {
        const float x = r.f32();
        if (!std::isfinite(x)) r.fail(std::string(what) + " is not a finite number");
        return x;
    };
    const size_t nv = s.vertices.size();
    if (flags & 1) {
        if (r.remaining() / 8 < nv) r.fail("the render surface's texture coordinates do not fit in the file");
        s.uv.resize(nv);
        for (auto& uv : s.uv) uv = {finite("a texture coordinate"), finite("a texture coordinate")};
    }
    if (flags & 2) {
        if (r.remaining() / 16 < nv) r.fail("the render surface's vertex colours do not fit in the file");
        s.colour.resize(nv);
        for (auto& c : s.colour)
            for (float& x : c) x = finite("a vertex colour");
    }
    if (flags & 4) {
        if (r.remaining() / 4 < s.triangles.size()) r.fail("the render surface's materials do not fit in the file");
        s.material.resize(s.triangles.size());
        for (uint32_t& m : s.material) m = r.u32();  // checked against the material table once it is read
    }
}

std::optional<RenderSurface> get_render_surface(ByteReader& r) {
    const uint8_t present = r.u8();
    if (present > 1) r.fail("render surface flag " + std::to_string(present) + " (0 or 1)");
    if (!present) return std::nullopt;
    RenderSurface s;
    const uint32_t nv = r.count(48, "render surface vertices");
    s.vertices.resize(nv);
    s.normals.resize(nv);
    for (uint32_t i = 0; i < nv; ++i) {
        s.vertices[i] = r.finite_vec3("a render surface vertex");
        s.normals[i] = r.finite_vec3("a render surface normal");
        if (std::abs(s.normals[i].norm() - 1) > 1e-3) r.fail("a render surface normal is not of unit length");
    }
    const uint32_t n = r.count(13, "render surface triangles");
    s.triangles.resize(n);
    s.kinds.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t& v : s.triangles[i]) v = r.index(nv, "render surface vertex index");
        uint8_t kind = r.u8();
        if (kind > static_cast<uint8_t>(FaceKind::Cavity)) r.fail("unknown face kind " + std::to_string(kind));
        s.kinds[i] = static_cast<FaceKind>(kind);
    }
    const uint8_t fell_back = r.u8();
    if (fell_back > 1) r.fail("render surface fell_back flag " + std::to_string(fell_back) + " (0 or 1)");
    s.fell_back = fell_back == 1;
    return s;
}

void put_piece(ByteWriter& w, const Piece& p) {
    w.u32(static_cast<uint32_t>(p.tets.size()));
    for (uint32_t t : p.tets) w.u32(t);
    put_surface(w, p.surface);
    w.f64(p.mass.volume);
    w.f64(p.mass.mass);
    w.vec3(p.mass.center);
    w.mat3(p.mass.inertia);
    w.u32(static_cast<uint32_t>(p.collision.size()));
    for (const ConvexPart& part : p.collision) {
        w.u32(static_cast<uint32_t>(part.points.size()));
        for (const Vec3& v : part.points) w.vec3(v);
        w.f64(part.volume);
        w.f64(part.hull_volume);
    }
    w.u8(p.connected ? 1 : 0);
    put_render_surface(w, p.render);
    if (p.render) put_appearance(w, *p.render);
}

Piece get_piece(ByteReader& r, uint32_t tet_count, uint32_t version) {
    Piece p;
    p.tets.resize(r.count(4, "piece tets"));
    for (uint32_t& t : p.tets) t = r.index(tet_count, "piece tet");
    p.surface = get_surface(r);
    p.mass.volume = r.finite_f64("piece volume");
    p.mass.mass = r.finite_f64("piece mass");
    p.mass.center = r.finite_vec3("centre of mass");
    p.mass.inertia = r.finite_mat3("inertia tensor");
    p.collision.resize(r.count(28, "collision parts"));
    for (ConvexPart& part : p.collision) {
        part.points.resize(r.count(24, "collision points"));
        for (Vec3& v : part.points) v = r.finite_vec3("a collision point");
        part.volume = r.finite_f64("collision part volume");
        part.hull_volume = r.finite_f64("collision hull volume");
    }
    p.connected = r.u8() != 0;
    if (version >= 2) p.render = get_render_surface(r);
    if (version >= 3 && p.render) get_appearance(r, *p.render);
    return p;
}

}  // namespace

void write_material(ByteWriter& w, const Material& m) {
    w.str(m.name);
    for (float x : m.base_colour) w.f32(x);
    w.u64(m.texture.size());
    w.bytes(m.texture);
    w.str(m.texture_mime);
    w.str(m.texture_name);
}

Material read_material(ByteReader& r) {
    Material m;
    m.name = r.str(4096);
    for (float& x : m.base_colour) {
        x = r.f32();
        if (!std::isfinite(x)) r.fail("a material's base colour is not a finite number");
    }
    const uint64_t n = r.u64();
    if (n > r.remaining()) r.fail("a material's texture claims " + std::to_string(n) + " bytes");
    m.texture = std::string(r.bytes(size_t(n)));
    m.texture_mime = r.str(256);
    m.texture_name = r.str(4096);
    return m;
}

std::string encode_model(const Model& m) {
    ByteWriter w;
    w.f64(m.density);
    w.u32(static_cast<uint32_t>(m.mesh.vertices.size()));
    for (const Vec3& v : m.mesh.vertices) w.vec3(v);
    w.u32(static_cast<uint32_t>(m.mesh.tets.size()));
    for (size_t t = 0; t < m.mesh.tets.size(); ++t) {
        for (uint32_t v : m.mesh.tets[t]) w.u32(v);
        w.u32(m.tet_piece[t]);
    }
    w.u32(static_cast<uint32_t>(m.pieces.size()));
    for (const Piece& p : m.pieces) put_piece(w, p);
    w.u32(static_cast<uint32_t>(m.constraints.size()));
    for (const Constraint& c : m.constraints) {
        w.u32(c.piece_a);
        w.u32(c.piece_b);
        w.u32(c.vertex);
        w.vec3(c.pivot);
        w.f64(c.area);
    }
    w.u32(static_cast<uint32_t>(m.materials.size()));
    for (const Material& mat : m.materials) write_material(w, mat);
    StageHeader h{std::string(kModelMagic), kModelVersion, m.producer, m.settings_json};
    return pack_stage_file(h, w.data());
}

Model decode_model(std::string_view bytes, const std::string& source) {
    StageFile f = unpack_stage_file(bytes, source, kModelMagic, "model", 1, kModelVersion);
    ByteReader r(f.payload, source, f.payload_offset);
    Model m;
    m.producer = f.header.producer;
    m.settings_json = f.header.settings_json;
    m.density = r.finite_f64("density");
    m.mesh.vertices.resize(r.count(24, "vertices"));
    for (Vec3& v : m.mesh.vertices) v = r.finite_vec3("a vertex");
    const uint32_t nv = static_cast<uint32_t>(m.mesh.vertices.size());
    const uint32_t nt = r.count(20, "tets");
    m.mesh.tets.resize(nt);
    m.tet_piece.resize(nt);
    for (uint32_t t = 0; t < nt; ++t) {
        for (uint32_t& v : m.mesh.tets[t]) v = r.index(nv, "tet vertex");
        m.tet_piece[t] = r.u32();
    }
    m.pieces.resize(r.count(1, "pieces"));
    const uint32_t np = static_cast<uint32_t>(m.pieces.size());
    for (uint32_t t = 0; t < nt; ++t)
        if (m.tet_piece[t] >= np) r.fail("tet " + std::to_string(t) + " names piece " + std::to_string(m.tet_piece[t]) +
                                         " of " + std::to_string(np));
    for (Piece& p : m.pieces) p = get_piece(r, nt, f.header.version);
    m.constraints.resize(r.count(44, "constraints"));
    for (Constraint& c : m.constraints) {
        c.piece_a = r.index(np, "constraint piece");
        c.piece_b = r.index(np, "constraint piece");
        c.vertex = r.index(nv, "constraint vertex");
        c.pivot = r.finite_vec3("constraint pivot");
        c.area = r.finite_f64("constraint area");
    }
    if (f.header.version >= 3) {
        m.materials.resize(r.count(29, "materials"));
        for (Material& mat : m.materials) mat = read_material(r);
        const uint32_t nm = static_cast<uint32_t>(m.materials.size());
        for (size_t p = 0; p < m.pieces.size(); ++p)
            if (m.pieces[p].render)
                for (uint32_t i : m.pieces[p].render->material)
                    if (i >= nm) r.fail("piece " + std::to_string(p) + "'s render surface names material " +
                                        std::to_string(i) + " of " + std::to_string(nm));
    }
    if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " unexpected bytes after the constraints");
    return m;
}

void save_model(const std::string& path, const Model& model) { write_file_atomic(path, encode_model(model)); }

Model load_model(const std::string& path) { return decode_model(read_file(path, "model file"), path); }

}  // namespace shatter
