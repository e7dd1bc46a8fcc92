// tetrahedralize: the closed mesh becomes a Surface_mesh (Epick), the domain a
// Polyhedral_mesh_domain_with_features_3 over it (sharp creases at least a tet long are
// protected, so boxes stay boxes), and make_mesh_3 refines sequentially without optimisers.
// Design notes and determinism: tetrahedralize.h.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "prescore/sharp_features.h"
#include "prescore/tetrahedralize.h"

namespace shatter {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Surface = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, Surface>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

void check_setting(const char* name, double value, double min, bool min_allowed, double max,
                   const char* unit) {
    const bool ok = std::isfinite(value) && (min_allowed ? value >= min : value > min) && value <= max;
    if (ok) return;
    std::ostringstream s;
    s << name << " = " << value << unit << " is outside " << (min_allowed ? "[" : "(") << min << ", "
      << max << "]";
    throw_input_error("tetrahedralize settings", s.str(),
                      "derive the sizes from the mesh with a resolution (cells per diagonal), e.g. 20");
}

void check_settings(const TetrahedralizeSettings& s) {
    const double inf = HUGE_VAL;
    check_setting("cell_size", s.cell_size, 0, false, inf, " m");
    check_setting("facet_size", s.facet_size, 0, false, inf, " m");
    check_setting("facet_distance", s.facet_distance, 0, false, inf, " m");
    check_setting("facet_angle", s.facet_angle, 0, false, 30, " degrees");
    check_setting("cell_radius_edge_ratio", s.cell_radius_edge_ratio, 2, true, inf, "");
    check_setting("feature_angle", s.feature_angle, 0, false, 180, " degrees");
}

// The mesh as a Surface_mesh (face i is triangle i). Adding the faces one by one rejects a
// non-manifold or misoriented mesh; this is ~5x faster than is_polygon_soup_a_polygon_mesh +
// polygon_soup_to_polygon_mesh on the bunny (measured 0.16 s for those two).
Surface to_surface(const TriangleMesh& mesh) {
    Surface surface;
    surface.reserve(mesh.vertices.size(), 3 * mesh.triangles.size() / 2, mesh.triangles.size());
    for (const Vec3& v : mesh.vertices) surface.add_vertex(Point(v.x(), v.y(), v.z()));
    for (const Tri& t : mesh.triangles) {
        using V = Surface::Vertex_index;
        if (surface.add_face(V(t[0]), V(t[1]), V(t[2])) == Surface::null_face()) {
            throw_input_error("tetrahedralize input",
                              "triangle (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                                  std::to_string(t[2]) +
                                  ") makes the mesh non-manifold, misoriented or degenerate",
                              "check the mesh (check_mesh) and repair it with alpha wrapping");
        }
    }
    if (mesh.triangles.empty() || !CGAL::is_closed(surface)) {
        throw_input_error("tetrahedralize input", "the mesh is not closed (it has boundary edges or no triangles)",
                          "repair it with alpha wrapping");
    }
    return surface;
}

// The complex's cells, vertices numbered by first use, each tet positively oriented.
TetMesh to_tet_mesh(const C3t3& c3t3) {
    TetMesh out;
    std::unordered_map<Tr::Vertex_handle, uint32_t> index;
    auto point_of = c3t3.triangulation().geom_traits().construct_point_3_object();
    for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
        Tet tet{};
        for (int i = 0; i < 4; ++i) {
            auto [it, inserted] = index.try_emplace(c->vertex(i), uint32_t(out.vertices.size()));
            if (inserted) {
                const Point p = point_of(c->vertex(i)->point());
                out.vertices.emplace_back(p.x(), p.y(), p.z());
            }
            tet[i] = it->second;
        }
        const auto& v = out.vertices;
        if (tet_volume(v[tet[0]], v[tet[1]], v[tet[2]], v[tet[3]]) < 0) std::swap(tet[2], tet[3]);
        out.tets.push_back(tet);
    }
    return out;
}

void log_cgal_warning(const char*, const char* expression, const char* file, int line, const char* message) {
    spdlog::debug("tetrahedralize: CGAL warning at {}:{} ({}): {}", file, line, expression, message ? message : "");
}

// The domain with its first surface points taken on the surface itself instead of on rays shot
// from the centre of its bounding box. Those rays must hit the surface, and on a thin flat wall
// whose box's centre lies outside it (a frame around a hole, a concave plate) few do, too close
// together: Mesh_3 then finds no facet to start from and makes nothing ("the mesh refinement
// process can't start"). Here a short segment across each of up to kSeeds faces, spread over the
// surface, gives the point and its surface index as the domain's own intersection does.
class SeededDomain : public Domain {
public:
    SeededDomain(const Surface& surface, double across) : Domain(surface) {
        const size_t faces = surface.number_of_faces();
        const size_t step = std::max<size_t>(1, faces / kSeeds);
        const auto intersect = construct_intersection_object();
        for (size_t f = 0; f < faces; f += step) {
            const auto h = surface.halfedge(Surface::Face_index(uint32_t(f)));
            const Point& a = surface.point(surface.source(h));
            const Point& b = surface.point(surface.target(h));
            const Point& c = surface.point(surface.target(surface.next(h)));
            const Kernel::Vector_3 n = CGAL::cross_product(b - a, c - a);
            const double length = std::sqrt(CGAL::to_double(n.squared_length()));
            if (!(length > 0)) continue;
            const Point centre = CGAL::centroid(a, b, c);
            const Kernel::Vector_3 d = n * (across / length);
            const Intersection hit = intersect(Kernel::Segment_3(centre - d, centre + d));
            if (std::get<2>(hit) != 0) seeds_.emplace_back(std::get<0>(hit), std::get<1>(hit));
        }
    }
    struct Construct_initial_points {
        const SeededDomain& domain;
        template <class OutputIterator>
        OutputIterator operator()(OutputIterator points, int = 0) const {
            return std::copy(domain.seeds_.begin(), domain.seeds_.end(), points);
        }
    };
    Construct_initial_points construct_initial_points_object() const { return {*this}; }

private:
    static constexpr size_t kSeeds = 64;
    std::vector<std::pair<Point, Index>> seeds_;
};

}  // namespace

TetrahedralizeSettings tetrahedralize_settings_for(double diagonal, double resolution) {
    check_setting("resolution", resolution, 0, false, HUGE_VAL, " cells per diagonal");
    check_setting("mesh bounding-box diagonal", diagonal, 0, false, HUGE_VAL, " m");
    TetrahedralizeSettings settings;
    settings.cell_size = diagonal / resolution;
    settings.facet_size = settings.cell_size;
    settings.facet_distance = settings.cell_size / 10;
    // The bunny's longest scan crease is 8% of its diagonal; a box's edges are far longer.
    settings.feature_min_length = 0.1 * diagonal;
    return settings;
}

TetMesh tetrahedralize(const TriangleMesh& closed_mesh, const TetrahedralizeSettings& settings) {
    check_settings(settings);
    const Surface surface = to_surface(closed_mesh);
    // Only creases at least as long as a tet and as feature_min_length are protected
    // (prescore/sharp_features.h).
    const double min_length = std::max(settings.cell_size, settings.feature_min_length);
    std::vector<std::vector<Point>> features;
    const std::vector<Polyline> creases =
        settings.protect_features ? sharp_polylines(closed_mesh, settings.feature_angle, min_length) : std::vector<Polyline>{};
    for (const Polyline& line : creases) {
        features.emplace_back();
        for (const Vec3& p : line) features.back().emplace_back(p.x(), p.y(), p.z());
    }

    namespace params = CGAL::parameters;
    const Criteria criteria(params::edge_size = settings.cell_size, params::facet_angle = settings.facet_angle,
                            params::facet_size = settings.facet_size,
                            params::facet_distance = settings.facet_distance,
                            params::cell_radius_edge_ratio = settings.cell_radius_edge_ratio,
                            params::cell_size = settings.cell_size);
    CGAL::parameters::internal::Mesh_3_options options;
    CGAL::Mesh_error_code error = CGAL::CGAL_MESH_3_NO_ERROR;
    options.maximal_number_of_vertices = settings.max_vertices;
    options.pointer_to_error_code = &error;
    const auto mesh = [&](auto& domain) {
        domain.add_features(features.begin(), features.end());
        // CGAL's warnings (a refinement that cannot start) go to the debug log: what follows from
        // them is this function's to report.
        const CGAL::Failure_function warn = CGAL::set_warning_handler(&log_cgal_warning);
        const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude(),
                                                  params::no_lloyd(), params::no_odt(), options);
        CGAL::set_warning_handler(warn);
        if (error == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED) {
            std::ostringstream s;
            s << "Mesh_3 reached its budget of " << settings.max_vertices << " vertices at cell size "
              << settings.cell_size << " m before the surface was followed";
            throw TetBudgetReached(ExitCode::BadInput, "tetrahedralize: " + s.str() +
                                                           " (fix: lower the resolution, or repair the mesh with "
                                                           "--repair always)");
        }
        return to_tet_mesh(c3t3);
    };
    Domain domain(surface);  // its random generator is CGAL::Random(0): deterministic
    TetMesh out = mesh(domain);
    if (out.tets.empty()) {  // no start from the rays: once more from points on the surface
        SeededDomain seeded(surface, settings.facet_distance);
        out = mesh(seeded);
    }
    if (out.tets.empty()) {
        std::ostringstream s;
        s << "Mesh_3 made no tets at cell size " << settings.cell_size
          << " m: the mesh is too thin for this resolution";
        throw_input_error("tetrahedralize", s.str(), "raise the resolution (smaller cells)");
    }
    return out;
}

}  // namespace shatter
