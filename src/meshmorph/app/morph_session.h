// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A case held in memory for repeated morphs, checks and writes: what the Python
//! module (python/) calls. Every morph starts from the mesh as read (its points x0), like a
//! morphMesh run on that case, so that the same prescriptions give the same points, bit for
//! bit, as the command line.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/morph/morph_stages.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/check_settings.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::app
{

//! How one patch moves in a morph with prescribed values.
struct PatchPrescription
{
    std::string patch; //!< a patch name of the mesh
    morph::MotionType type =
        morph::MotionType::fixed;     //!< fixed, slip, free, translate or point_displacement
    Vector3 vector = Vector3::Zero(); //!< translate
    Points values;                    //!< point_displacement: nPatchPoints x 3, patch-local order
};

//! Mesh points moved by given displacements (they override the patches' prescriptions, as
//! morphDict handles do).
struct PointSetPrescription
{
    std::string name;
    std::vector<Index> labels;
    Points displacements; //!< labels.size() x 3
};

//! Prescriptions given as values instead of a morphDict's `boundary` entries. Patches not
//! named keep the morphDict's entries (or are fixed without a morphDict).
struct Prescriptions
{
    std::vector<PatchPrescription> patches;
    std::vector<PointSetPrescription> point_sets;
};

//! A case read once; morphed, checked and written any number of times.
class MorphSession
{
public:
    //! Reads the mesh of options (case, region, time); the morphDict is read by each morph.
    //! -parallel is not supported. \throw IoError, ParseError, InvalidInput.
    explicit MorphSession(const morph::MorphOptions& options);

    const io::FoamPolyMesh& foam() const { return in_.foam; }
    const PolyMesh& mesh() const { return in_.foam.mesh; }
    const std::filesystem::path& case_dir() const { return case_dir_; }
    const morph::MorphOptions& options() const { return options_; }
    //! The points as read (x0), which every morph starts from.
    const Points& initial_points() const { return in_.foam.mesh.points; }
    //! The current points: x0, the last morph's, or those set.
    const Points& points() const { return moved_->points; }
    //! \brief Replace the current points. \throw InvalidInput for a wrong row count or a
    //! non-finite coordinate.
    void set_points(Points points);
    //! Back to x0.
    void reset();

    //! \brief Morph with the morphDict (options' or `dict`, relative to the case), in
    //! memory. \throw as morphMesh (ParseError, InvalidInput, IoError, SolverError).
    const morph::MorphResult& morph(const std::optional<std::filesystem::path>& dict = {});
    //! \brief Morph with prescribed values; the morphDict, when the case has one, gives the
    //! method, its settings and the patches not named. \throw InvalidInput naming the patch
    //! or point set for a wrong shape, an unknown patch or label, a non-finite value.
    const morph::MorphResult& morph(const Prescriptions& prescriptions);
    //! \brief The reverse pass of the last morph: for dJ/dx at every mesh point (nPoints x 3)
    //! dJ/dH, the derivative with respect to each constrained point's prescribed
    //! displacement (nPoints x 3, zero at the other points). The transpose of the morph's
    //! field with its choices held (greedy centres, jumps, the IDW tree), refitted as the
    //! morph fitted it. Points the morph's local repair moved are taken as following the
    //! field (a warning says how many). \throw InvalidInput before a morph, for a morph in
    //! more than one step (not one field), or for what morph::morph_points_transpose does not
    //! cover.
    Points sensitivity(const Points& dJdx) const;
    //! The last morph's result (empty before the first).
    const morph::MorphResult& result() const { return result_; }

    //! checkMesh's report of the current points.
    QualityReport check(const CheckMeshSettings& settings) const;
    //! \brief Whether the current points have no more negative-volume cells and wrongly
    //! oriented face pyramids than x0: the two checks a morph is judged by, nothing else.
    bool is_valid() const;

    //! \brief Write the current points atomically: to the next time after the mesh's, or
    //! with overwrite into the mesh's own instance (the original kept as points.orig).
    //! \return the file written. \throw IoError.
    std::filesystem::path write(bool overwrite);

private:
    //! The check of x0, computed once, on first use.
    const QualityReport& before();
    void run_morph(const morph::MorphOptions& options, const morph::PointDisplacementInputs* given);

    morph::MorphOptions options_;
    std::filesystem::path case_dir_, dict_path_; //!< absolute; the options' morphDict
    morph::MorphCase in_;
    CompactList cell_faces_;
    std::optional<PolyMesh> moved_; //!< the topology of in_.foam.mesh with the current points
    std::optional<QualityReport> before_;
    mutable std::optional<InvalidCells> invalid_before_; //!< of x0, on first use
    morph::MorphResult result_;
};

} // namespace meshmorph::app
