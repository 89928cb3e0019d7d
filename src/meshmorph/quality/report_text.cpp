// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh's report text (OpenFOAM v1912 checkMesh.C, checkTopology.C, checkGeometry.C and
// the primitiveMesh::check* report lines; docs/checkmesh-spec.md).
#include "meshmorph/quality/report_text.h"
#include "meshmorph/core/number_format.h"

#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace meshmorph
{

namespace
{

//! The report being written, with OpenFOAM's number formatting.
class Writer
{
public:
    Writer(const QualityReport& report_in, const CheckMeshSettings& settings_in)
        : report(report_in), settings(settings_in),
          right_justify_(report_in.cell_types.polyhedron > 0)
    {
    }
    std::string s(double v) const { return format_scalar(v, settings.write_precision); }
    //! A vector as OpenFOAM writes it: (x y z).
    std::string v(const Vector3& x) const
    {
        std::string text(1, '(');
        text.append(s(x.x())).append(1, ' ').append(s(x.y())).append(1, ' ').append(s(x.z()));
        return text.append(1, ')');
    }
    //! Justified in `width` columns (std::setw). checkMesh's tables are left-justified,
    //! except after a polyhedra breakdown: v1912 sets ios::right there and never resets it,
    //! so every later table is right-justified.
    std::string w(const std::string& text, std::size_t width) const
    {
        if (text.size() >= width)
            return text;
        const std::string fill(width - text.size(), ' ');
        return right_justify_ ? fill + text : text + fill;
    }

    std::ostringstream out;
    const QualityReport& report;
    const CheckMeshSettings& settings;

private:
    bool right_justify_;
};

//! The lines of one check; its sets' "<<Writing" lines follow.
using Formatter = void (*)(const CheckResult&, Writer&);

// ---------------------------------------------------------------------------------------
// Topology

void boundary_definition(const CheckResult& c, Writer& t)
{
    t.out << (c.count("boundaryDefinitionOK") ? "    Boundary definition OK.\n"
                                              : " ***Boundary definition is in error.\n");
}

void empty_patches(const CheckResult& c, Writer& t)
{
    if (!c.count("emptyFacesDivisible"))
        t.out << " ***Total number of faces on empty patches is not divisible by the number of "
                 "cells in the mesh. Hence this mesh is not 1D or 2D.\n";
}

void cell_addressing(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << "    Illegal cells (less than 4 faces or out of range faces) found,  number of "
                 "cells: "
              << c.count("illegalCells") << "\n";
    else
        t.out << "    Cell to face addressing OK.\n";
}

void point_usage(const CheckResult& c, Writer& t)
{
    const Index n = c.count("unusedPoints");
    if (c.failed())
        t.out << " ***Unused points found in the mesh, number unused by faces: " << n
              << " number unused by cells: " << n << "\n";
    else
        t.out << "    Point usage OK.\n";
}

void upper_triangular(const CheckResult& c, Writer& t)
{
    if (const Index n = c.count("cellsWithMultipleFaces"); n > 0)
        t.out << "  <<Found " << n << " neighbouring cells with multiple inbetween faces.\n";
    t.out << (c.failed() ? " ***Faces not in upper triangular order.\n"
                         : "    Upper triangular ordering OK.\n");
}

void face_vertices(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << "    Faces with invalid vertex labels found,  number of faces: "
              << c.count("faceVertexErrors") << "\n";
    else
        t.out << "    Face vertices OK.\n";
}

void cells_zip_up(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Open cells found, number of cells: " << c.count("openCells")
              << ". This problem may be fixable using the zipUpMesh utility.\n";
    else
        t.out << "    Topological cell zip-up check OK.\n";
}

void face_faces(const CheckResult& c, Writer& t)
{
    const Index baffles = c.count("baffleFaces"), duplicates = c.count("duplicateFaces");
    const Index order_errors = c.count("nonConsecutiveFaces");
    if (baffles > 0)
        t.out << "    Number of identical duplicate faces (baffle faces): " << baffles << "\n";
    if (duplicates > 0)
        t.out << "  <<Number of duplicate (not baffle) faces found: " << duplicates
              << ". This might indicate a problem.\n";
    if (order_errors > 0)
        t.out << "  <<Number of faces with non-consecutive shared points: " << order_errors
              << ". This might indicate a problem.\n";
    if (duplicates == 0 && order_errors == 0)
        t.out << "    Face-face connectivity OK.\n";
}

void no_lines(const CheckResult&, Writer&) {}

void regions(const CheckResult& c, Writer& t)
{
    const Index n = c.count("regions");
    if (n <= 1)
    {
        t.out << "    Number of regions: " << n << " (OK).\n";
        return;
    }
    t.out << "   *Number of regions: " << n << "\n"
          << "    The mesh has multiple regions which are not connected by any face.\n";
    if (!t.settings.report_sets)
        return;
    // A fileName is written in quotes.
    t.out << "  <<Writing region information to \"" << t.settings.time_name << "/cellToRegion\"\n";
    // -allTopology says how each region touches the others.
    const Statistic* disconnected = c.find("regionDisconnected");
    for (std::size_t i = 0; i < static_cast<std::size_t>(n) && i < c.sets.size(); ++i)
    {
        t.out << "  <<Writing region " << i;
        if (disconnected)
            t.out << (std::get<Statistic::Counts>(disconnected->value).at(i).second
                          ? " (fully disconnected)"
                          : " (point connected)");
        t.out << " with " << c.sets[i].size() << " cells to cellSet " << c.sets[i].set.name << "\n";
    }
}

// ---------------------------------------------------------------------------------------
// Geometry

void edge_alignment(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Number of edges not aligned with or perpendicular to non-empty "
                 "directions: "
              << c.count("nonAlignedEdges") << "\n";
    else
        t.out << "    All edges aligned with or perpendicular to non-empty directions.\n";
}

void wedges(const CheckResult& c, Writer& t)
{
    const Statistic::Reals& angles = c.reals("wedgeAngles");
    for (const auto& [name, angle] : angles)
        t.out << "    Wedge " << name << " with angle " << t.s(angle) << " degrees\n";
    // checkWedges stops at the first problem: it is the last wedge's.
    const std::string name = angles.empty() ? "" : angles.back().first;
    if (c.failure == "wedgeOpposite")
        t.out << " ***Cannot find opposite wedge for wedge " << name << "\n";
    else if (c.failure == "wedgeAxes")
    {
        // (sic: v1912 prints the opposite axis twice, the second without a space)
        const std::string opposite = t.v(c.vector("oppositeWedgeAxis"));
        t.out << " ***Wedges do not have the same axis. Encountered " << t.v(c.vector("wedgeAxis"))
              << " on patch " << name << " which differs from " << opposite
              << " on opposite wedge patch" << opposite << "\n";
    }
    else if (c.failure == "wedgePlanarity")
        t.out << " ***Wedge patch " << name << " not planar. Point "
              << t.v(c.vector("offPlanePoint")) << " is not in patch plane by "
              << t.s(c.real("offPlaneDistance")) << " metre.\n";
    else
        edge_alignment(c, t);
}

void closed_boundary(const CheckResult& c, Writer& t)
{
    const std::string o = t.v(c.vector("boundaryOpenness"));
    if (c.failed())
        t.out << " ***Boundary openness " << o << " possible hole in boundary description.\n";
    else
        t.out << "    Boundary openness " << o << " OK.\n";
}

void closed_cells(const CheckResult& c, Writer& t)
{
    const double max_open = c.real("maxCellOpenness"), max_ar = c.real("maxAspectRatio");
    if (const Index n = c.count("openCells"); n > 0)
        t.out << " ***Open cells found, max cell openness: " << t.s(max_open)
              << ", number of open cells " << n << "\n";
    else if (const Index n_ar = c.count("highAspectRatioCells"); n_ar > 0)
        t.out << " ***High aspect ratio cells found, Max aspect ratio: " << t.s(max_ar)
              << ", number of cells " << n_ar << "\n";
    else
        t.out << "    Max cell openness = " << t.s(max_open) << " OK.\n"
              << "    Max aspect ratio = " << t.s(max_ar) << " OK.\n";
}

void face_areas(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Zero or negative face area detected.  Minimum area: "
              << t.s(c.real("minFaceArea")) << "\n";
    else
        t.out << "    Minimum face area = " << t.s(c.real("minFaceArea"))
              << ". Maximum face area = " << t.s(c.real("maxFaceArea"))
              << ".  Face area magnitudes OK.\n";
}

void cell_volumes(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Zero or negative cell volume detected.  Minimum negative volume: "
              << t.s(c.real("minVolume"))
              << ", Number of negative volume cells: " << c.count("negativeVolumeCells") << "\n";
    else
        t.out << "    Min volume = " << t.s(c.real("minVolume"))
              << ". Max volume = " << t.s(c.real("maxVolume"))
              << ".  Total volume = " << t.s(c.real("totalVolume")) << ".  Cell volumes OK.\n";
}

void face_orthogonality(const CheckResult& c, Writer& t)
{
    if (c.count("summedFaces") > 0)
        t.out << "    Mesh non-orthogonality Max: " << t.s(c.real("maxNonOrthogonality"))
              << " average: " << t.s(c.real("avgNonOrthogonality")) << "\n";
    if (const Index severe = c.count("severelyNonOrthogonalFaces"); severe > 0)
        t.out << "   *Number of severely non-orthogonal (> 70 degrees) faces: " << severe << ".\n";
    if (c.failed())
        t.out << " ***Number of non-orthogonality errors: " << c.count("nonOrthogonalityErrors")
              << ".\n";
    else
        t.out << "    Non-orthogonality check OK.\n";
}

void face_pyramids(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Error in face pyramids: " << c.count("incorrectlyOrientedFacePyramids")
              << " faces are incorrectly oriented.\n";
    else
        t.out << "    Face pyramids OK.\n";
}

void face_skewness(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Max skewness = " << t.s(c.real("maxSkewness")) << ", "
              << c.count("highlySkewedFaces")
              << " highly skew faces detected which may impair the quality of the results\n";
    else
        t.out << "    Max skewness = " << t.s(c.real("maxSkewness")) << " OK.\n";
}

void coupled_points(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << "  **Error in coupled point location: " << c.count("mismatchedCoupledFaces")
              << " faces have their 0th or consecutive vertex not opposite their coupled"
                 " equivalent. Average mismatch "
              << t.s(c.real("averageCoupledMismatch")) << ".\n";
    else
        t.out << "    Coupled point location match (average "
              << t.s(c.real("averageCoupledMismatch")) << ") OK.\n";
}

void face_tets(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Error in face tets: " << c.count("faceTetErrors")
              << " faces with low quality or negative volume decomposition tets.\n";
    else
        t.out << "    Face tets OK.\n";
}

void edge_length(const CheckResult& c, Writer& t)
{
    const std::string lengths = t.s(c.real("minEdgeLength")) + " " + t.s(c.real("maxEdgeLength"));
    if (const Index n = c.count("shortEdges"); n > 0)
        t.out << "   *Edges too small, min/max edge length = " << lengths
              << ", number too small: " << n << "\n";
    else
        t.out << "    Min/max edge length = " << lengths << " OK.\n";
}

//! After the shortEdges line: checkMesh's point nearness set (points on short edges and
//! points closer than the same distance), written when it has more points.
void near_points(const CheckResult& c, Writer& t)
{
    for (const OffenderSet& s : c.sets)
        if (s.set.name == "nearPoints")
            t.out << "  <<Writing " << s.size() << " near (closer than "
                  << t.s(c.real("nearPointDistance")) << " apart) points to set nearPoints\n";
}

void face_angles(const CheckResult& c, Writer& t)
{
    if (const Index n = c.count("concaveFaces"); n > 0)
        t.out << "   *There are " << n
              << " faces with concave angles between consecutive edges. Max concave angle = "
              << t.s(c.real("maxConcaveAngle")) << " degrees.\n";
    else
        t.out << "    All angles in faces OK.\n";
}

void face_flatness(const CheckResult& c, Writer& t)
{
    const double min = c.real("minFaceFlatness");
    if (c.count("flatnessFaces") > 0)
        t.out << "    Face flatness (1 = flat, 0 = butterfly) : min = " << t.s(min)
              << "  average = " << t.s(c.real("avgFaceFlatness")) << "\n";
    if (const Index n = c.count("warpedFaces"); n > 0)
        t.out << "   *There are " << n
              << " faces with ratio between projected and actual area < 0.8\n"
              << "    Minimum ratio (minimum flatness, maximum warpage) = " << t.s(min) << "\n";
    else
        t.out << "    All face flatness OK.\n";
}

void cell_determinant(const CheckResult& c, Writer& t)
{
    if (t.report.n_cells > 0)
        t.out << "    Cell determinant (wellposedness) : minimum: " << t.s(c.real("minDeterminant"))
              << " average: " << t.s(c.real("avgDeterminant")) << "\n";
    if (c.failed())
        t.out << " ***Cells with small determinant (< 0.001) found, number of cells: "
              << c.count("smallDeterminantCells") << "\n";
    else
        t.out << "    Cell determinant check OK.\n";
}

void concave_cells(const CheckResult& c, Writer& t)
{
    if (c.failed())
        t.out << " ***Concave cells (using face planes) found, number of cells: "
              << c.count("concaveCells") << "\n";
    else
        t.out << "    Concave cell check OK.\n";
}

//! Face weights and volume ratios: "<what> : minimum: .. average: ..", then the verdict.
void low_values(const CheckResult& c, Writer& t, std::string_view what, std::string_view limit,
                std::string_view min_key, std::string_view avg_key, std::string_view count_key)
{
    if (c.count("summedFaces") > 0)
        t.out << "    Face " << what << " : minimum: " << t.s(c.real(min_key))
              << " average: " << t.s(c.real(avg_key)) << "\n";
    if (c.failed())
        t.out << " ***Faces with small " << what << " (< " << limit
              << ") found, number of faces: " << c.count(count_key) << "\n";
    else
        t.out << "    Face " << what << " check OK.\n";
}

void face_weight(const CheckResult& c, Writer& t)
{
    low_values(c, t, "interpolation weight", "0.05", "minFaceWeight", "avgFaceWeight",
               "lowWeightFaces");
}

void volume_ratio(const CheckResult& c, Writer& t)
{
    low_values(c, t, "volume ratio", "0.01", "minVolumeRatio", "avgVolumeRatio",
               "lowVolumeRatioFaces");
}

// ---------------------------------------------------------------------------------------
// -meshQuality

//! The line of a meshQualityDict criterion, up to its count.
std::string criterion_line(const std::string& key, const Writer& t)
{
    const MeshQualitySettings& q = *t.settings.mesh_quality;
    const auto limit = [&](double v, std::size_t width) { return t.w(t.s(v), width); };
    if (key == "maxNonOrtho")
        return "    non-orthogonality > " + limit(q.max_non_ortho, 3) +
               " degrees                        : ";
    if (key == "minVol")
        return "    faces with face pyramid volume < " + limit(q.min_vol, 5) +
               "                 : ";
    if (key == "minTetQuality")
        return "    faces with face-decomposition tet quality < " + limit(q.min_tet_quality, 5) +
               "      : ";
    if (key == "maxConcave")
        return "    faces with concavity > " + limit(q.max_concave, 3) +
               " degrees                     : ";
    if (key == "minArea")
        return "    faces with area < " + limit(q.min_area, 5) +
               " m^2                            : ";
    if (key == "maxInternalSkewness")
        return "    faces with skewness > " + limit(q.max_internal_skewness, 3) +
               " (internal) or " + limit(q.max_boundary_skewness, 3) + " (boundary) : ";
    if (key == "minFaceWeight")
        return "    faces with interpolation weights (0..1)  < " + limit(q.min_face_weight, 5) +
               "       : ";
    if (key == "minVolRatio")
        return "    faces with volume ratio of neighbour cells < " + limit(q.min_vol_ratio, 5) +
               "     : ";
    if (key == "minTwist")
        return "    faces with face twist < " + limit(q.min_twist, 5) +
               "                          : ";
    if (key == "minTriangleTwist")
        return "    faces with triangle twist < " + limit(q.min_triangle_twist, 5) +
               "                      : ";
    if (key == "minFaceFlatness")
        return "    faces with flatness < " + limit(q.min_face_flatness, 5) +
               "                      : ";
    if (key == "minDeterminant")
        return "    faces on cells with determinant < " + limit(q.min_determinant, 5) +
               "                : ";
    throw std::logic_error("no report line for meshQualityDict criterion " + key);
}

void mesh_quality(const CheckResult& c, Writer& t)
{
    t.out << "Checking faces in error :\n";
    for (const auto& [key, count] : c.counts("meshQualityFailures"))
        t.out << criterion_line(key, t) << count << "\n";
}

// ---------------------------------------------------------------------------------------
// The table and the sections

enum class Section
{
    topology,
    geometry
};

struct Format
{
    CheckId id;
    Section section;
    Formatter print;
    //! Lines after the sets' "<<Writing" lines (-writeSets only), or nullptr.
    Formatter after_sets;
};

const Format formats[] = {
    {CheckId::boundary_definition, Section::topology, boundary_definition, nullptr},
    {CheckId::empty_patches, Section::topology, empty_patches, nullptr},
    {CheckId::cell_addressing, Section::topology, cell_addressing, nullptr},
    {CheckId::point_usage, Section::topology, point_usage, nullptr},
    {CheckId::upper_triangular, Section::topology, upper_triangular, nullptr},
    {CheckId::face_vertices, Section::topology, face_vertices, nullptr},
    {CheckId::cells_zip_up, Section::topology, cells_zip_up, nullptr},
    {CheckId::face_faces, Section::topology, face_faces, nullptr},
    {CheckId::internal_face_cells, Section::topology, no_lines, nullptr},
    {CheckId::regions, Section::topology, regions, nullptr},
    {CheckId::edge_alignment, Section::geometry, edge_alignment, nullptr},
    {CheckId::wedges, Section::geometry, wedges, nullptr},
    {CheckId::closed_boundary, Section::geometry, closed_boundary, nullptr},
    {CheckId::closed_cells, Section::geometry, closed_cells, nullptr},
    {CheckId::face_areas, Section::geometry, face_areas, nullptr},
    {CheckId::cell_volumes, Section::geometry, cell_volumes, nullptr},
    {CheckId::face_orthogonality, Section::geometry, face_orthogonality, nullptr},
    {CheckId::face_pyramids, Section::geometry, face_pyramids, nullptr},
    {CheckId::face_skewness, Section::geometry, face_skewness, nullptr},
    {CheckId::coupled_points, Section::geometry, coupled_points, nullptr},
    {CheckId::face_tets, Section::geometry, face_tets, nullptr},
    {CheckId::edge_length, Section::geometry, edge_length, near_points},
    {CheckId::face_angles, Section::geometry, face_angles, nullptr},
    {CheckId::face_flatness, Section::geometry, face_flatness, nullptr},
    {CheckId::cell_determinant, Section::geometry, cell_determinant, nullptr},
    {CheckId::concave_cells, Section::geometry, concave_cells, nullptr},
    {CheckId::face_weight, Section::geometry, face_weight, nullptr},
    {CheckId::volume_ratio, Section::geometry, volume_ratio, nullptr},
    {CheckId::mesh_quality, Section::geometry, mesh_quality, nullptr},
};

const Format& format_of(const CheckResult& c)
{
    for (const Format& f : formats)
        if (f.id == c.id)
            return f;
    throw std::logic_error("the report has no formatter for check " +
                           std::string(check_name(c.id)));
}

//! Every check of `section`, in order, each followed by its sets' "<<Writing" lines.
void print_checks(Section section, Writer& t)
{
    for (const CheckResult& c : t.report.checks)
    {
        const Format& format = format_of(c);
        if (format.section != section)
            continue;
        format.print(c, t);
        if (!t.settings.report_sets)
            continue;
        for (const OffenderSet& s : c.sets)
            if (!s.description.empty())
                t.out << "  <<Writing " << s.size() << " " << s.description << " to set "
                      << s.set.name << "\n";
        if (format.after_sets)
            format.after_sets(c, t);
    }
}

//! "boundary patches: N", or in parallel "N (min max)" with the range of patches per rank.
std::string boundary_patches(const QualityReport& r)
{
    if (!r.parallel)
        return std::to_string(r.n_patches);
    return std::to_string(r.parallel->non_processor_patches) + " (" +
           std::to_string(r.parallel->min_patches) + " " + std::to_string(r.parallel->max_patches) +
           ")";
}

void mesh_stats(Writer& t)
{
    const QualityReport& r = t.report;
    std::ostringstream& out = t.out;
    // checkMesh -parallel prints the ranks' counts summed.
    const Index n_points = r.parallel ? r.parallel->summed_points : r.n_points;
    const Index n_faces = r.parallel ? r.parallel->summed_faces : r.n_faces;
    const Index n_internal = r.parallel ? r.parallel->summed_internal_faces : r.n_internal_faces;
    out << "Mesh stats\n"
        << "    points:           " << n_points << "\n";
    if (r.n_internal_points >= 0)
        out << "    internal points:  " << r.n_internal_points << "\n";
    if (r.edges)
        out << "    edges:            " << r.edges->edges << "\n"
            << "    internal edges:   " << r.edges->internal_edges << "\n"
            << "    internal edges using one boundary point:   "
            << r.edges->internal_edges_one_boundary_point << "\n"
            << "    internal edges using two boundary points:  "
            << r.edges->internal_edges_two_boundary_points << "\n";
    out << "    faces:            " << n_faces << "\n"
        << "    internal faces:   " << n_internal << "\n"
        << "    cells:            " << r.n_cells << "\n"
        << "    faces per cell:   "
        << t.s(double(n_faces + n_internal) / std::max<Index>(1, r.n_cells)) << "\n"
        << "    boundary patches: " << boundary_patches(r) << "\n"
        << "    point zones:      " << r.n_point_zones << "\n"
        << "    face zones:       " << r.n_face_zones << "\n"
        << "    cell zones:       " << r.n_cell_zones << "\n\n";
}

void cell_types(Writer& t)
{
    const CellShapeCounts& counts = t.report.cell_types;
    std::ostringstream& out = t.out;
    out << "Overall number of cells of each type:\n"
        << "    hexahedra:     " << counts.hex << "\n"
        << "    prisms:        " << counts.prism << "\n"
        << "    wedges:        " << counts.wedge << "\n"
        << "    pyramids:      " << counts.pyramid << "\n"
        << "    tet wedges:    " << counts.tet_wedge << "\n"
        << "    tetrahedra:    " << counts.tet << "\n"
        << "    polyhedra:     " << counts.polyhedron << "\n";
    if (counts.polyhedron > 0)
    {
        out << "    Breakdown of polyhedra by number of faces:\n"
            << "        faces   number of cells\n";
        for (const auto& [n_faces, n] : counts.polyhedra_by_faces)
            out << std::setw(13) << std::right << n_faces << "   " << n << "\n";
    }
    out << "\n";
}

//! A patch or faceZone table; checkMesh -parallel leaves out the surface topology column.
void surface_table(const std::string& what, const std::vector<SurfaceTopology>& rows, Writer& t)
{
    const bool all_geometry = t.settings.all_geometry;
    const bool topology = !t.report.parallel;
    t.out << "    " << t.w(what, 20) << t.w("Faces", 9) << t.w("Points", 9)
          << (topology ? t.w("Surface topology", 34) : "") << (all_geometry ? " Bounding box" : "")
          << "\n";
    for (const SurfaceTopology& s : rows)
    {
        t.out << "    " << t.w(s.name, 20) << t.w(std::to_string(s.n_faces), 9)
              << t.w(std::to_string(s.n_points), 9) << (topology ? t.w(s.type, 34) : "");
        if (all_geometry && s.n_points > 0)
            t.out << ' ' << t.v(s.bb_min) << " " << t.v(s.bb_max);
        t.out << "\n";
    }
}

void topology_tables(Writer& t)
{
    const QualityReport& r = t.report;
    // checkMesh -parallel checks the addressing only: a surface split over ranks has no
    // topology to classify.
    t.out << (r.parallel ? "\nChecking basic patch addressing...\n"
                         : "\nChecking patch topology for multiply connected surfaces...\n");
    surface_table("Patch", r.patch_topology, t);
    t.out << (r.parallel ? "\nChecking basic faceZone addressing...\n"
                         : "\nChecking faceZone topology for multiply connected surfaces...\n");
    if (r.face_zone_topology.empty())
        t.out << "    No faceZones found.\n";
    else
        surface_table("FaceZone", r.face_zone_topology, t);
    if (t.settings.report_sets && r.non_manifold_total > 0)
        t.out << "  <<Writing " << r.non_manifold_total
              << " conflicting points to set nonManifoldPoints\n";
    t.out << "\nChecking basic cellZone addressing...\n";
    if (r.cell_zones.empty())
        t.out << "    No cellZones found.\n";
    else
    {
        t.out << "    " << t.w("CellZone", 20) << t.w("Cells", 13) << t.w("Points", 13)
              << t.w("Volume", 13) << "BoundingBox\n";
        for (const CellZoneSummary& z : r.cell_zones)
            t.out << "    " << t.w(z.name, 19) << ' ' << t.w(std::to_string(z.n_cells), 12) << ' '
                  << t.w(std::to_string(z.n_points), 12) << ' ' << t.w(t.s(z.volume), 12) << ' '
                  << t.v(z.bb_min) << " " << t.v(z.bb_max) << "\n";
    }
    t.out << "\n";
}

void domain(Writer& t)
{
    const QualityReport& r = t.report;
    const MeshDirections& dirs = r.directions;
    const Eigen::Vector3i valid = (dirs.geometric + Eigen::Vector3i::Ones()) / 2;
    const Eigen::Vector3i sol = (dirs.solution + Eigen::Vector3i::Ones()) / 2;
    t.out << "    Overall domain bounding box " << t.v(r.bounding_box_min) << " "
          << t.v(r.bounding_box_max) << "\n"
          << "    Mesh has " << dirs.n_geometric() << " geometric (non-empty/wedge) directions ("
          << valid[0] << " " << valid[1] << " " << valid[2] << ")\n"
          << "    Mesh has " << dirs.n_solution() << " solution (non-empty) directions (" << sol[0]
          << " " << sol[1] << " " << sol[2] << ")\n";
}

} // namespace

std::string report_text(const QualityReport& report, const CheckMeshSettings& settings)
{
    Writer t(report, settings);
    mesh_stats(t);
    cell_types(t);
    if (!settings.no_topology)
    {
        t.out << "Checking topology...\n";
        print_checks(Section::topology, t);
        topology_tables(t);
    }
    t.out << "Checking geometry...\n";
    domain(t);
    print_checks(Section::geometry, t);
    if (report.failed_checks == 0)
        t.out << "\nMesh OK.\n";
    else
        t.out << "\nFailed " << report.failed_checks << " mesh checks.\n";
    return t.out.str();
}

} // namespace meshmorph
