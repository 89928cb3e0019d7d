// SPDX-License-Identifier: GPL-3.0-or-later
// A pointVectorField in OpenFOAM's ASCII form.
#include "meshmorph/io/point_field_writer.h"

#include <algorithm>
#include <array>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/io/foam_file.h"

namespace meshmorph::io
{
namespace
{

//! The point patch types OpenFOAM derives from the patch and requires to match it.
bool is_constraint_type(const std::string& type)
{
    static const std::array<std::string, 9> types = {
        "empty",     "wedge",      "symmetry",  "symmetryPlane",  "cyclic",
        "cyclicAMI", "cyclicSlip", "processor", "processorCyclic"};
    return std::find(types.begin(), types.end(), type) != types.end();
}

void write_vector(std::ostream& out, const Eigen::RowVector3d& v)
{
    out << '(' << format_scalar(v[0], 17) << ' ' << format_scalar(v[1], 17) << ' '
        << format_scalar(v[2], 17) << ")\n";
}

//! `nonuniform List<vector> n ( ... )` for the rows `rows` of values (all rows if null).
void write_list(std::ostream& out, const Points& values, const std::vector<Index>* rows)
{
    const std::size_t n = rows ? rows->size() : std::size_t(values.rows());
    out << "nonuniform List<vector> " << n << "\n(\n";
    for (std::size_t i = 0; i < n; ++i)
        write_vector(out, values.row(rows ? (*rows)[i] : Eigen::Index(i)));
    out << ")";
}

} // namespace

std::filesystem::path write_point_vector_field(const std::filesystem::path& path,
                                               const PolyMesh& mesh, const Points& values,
                                               const std::string& location, const std::string& note)
{
    if (values.rows() != mesh.n_points())
        throw InvalidInput(path.string() + ": " + std::to_string(values.rows()) +
                           " values for a mesh of " + std::to_string(mesh.n_points()) + " points");
    std::ostringstream out;
    if (!note.empty())
        out << "// " << note << "\n";
    out << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
        << "    class       pointVectorField;\n    location    \"" << location << "\";\n"
        << "    object      " << path.filename().string() << ";\n}\n\n"
        << "dimensions      [0 0 0 0 0 0 0];\n\ninternalField   ";
    write_list(out, values, nullptr);
    out << ";\n\nboundaryField\n{\n";
    for (const Patch& patch : mesh.patches)
    {
        out << "    " << patch.name << "\n    {\n";
        if (is_constraint_type(patch.type))
            out << "        type            " << patch.type << ";\n";
        else
        {
            const std::vector<Index> points = patch_points(mesh, patch);
            out << "        type            calculated;\n        value           ";
            write_list(out, values, &points);
            out << ";\n";
        }
        out << "    }\n";
    }
    out << "}\n";
    return write_file_atomic(path, out.str());
}

} // namespace meshmorph::io
