// SPDX-License-Identifier: GPL-3.0-or-later
//! \file `morphMesh -variant` and `-variants`: designs from a stored set-up (design_setup.h),
//! x = x0 + sum_j a_j F_j, with the checks of a normal morph: exactness at the constrained
//! points, checkMesh's metrics, refusal of new invalid cells (then the variable whose
//! removal repairs most is named), atomic writing.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/design/design_basis.h"
#include "meshmorph/design/design_case.h"
#include "meshmorph/design/variant_repair.h"
#include "meshmorph/morph/invalid_cells_location.h"
#include "meshmorph/morph/morph_result.h"
#include "meshmorph/morph/new_check_failures.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::design
{

class SharedDesignFit;

//! A variant whose linear combination adds more new invalid cells and face pyramids than
//! this fraction of the cells is refused without untangling: the local repair is for a few
//! cells (a sliver between a moving wall and a fixed one), and on damage that wide it only
//! spends time (41% of the tutorial pipe's cells: 2 s, then 760 cells still invalid).
inline constexpr double max_untangled_fraction = 0.05;

//! A shared set-up's refusal names a variable to back off only when at most this many are
//! not zero: each one tried is a variant (a held evaluation), not a sum of stored fields.
inline constexpr long max_back_off_evaluations = 16;

//! What one variant did.
struct VariantResult
{
    std::vector<double> amplitudes;
    double max_prescribed = 0.0;       //!< largest prescribed displacement
    double max_constraint_error = 0.0; //!< max |x - x0 - prescribed| at the constrained points
    double relative_constraint_error = 0.0;
    double max_displacement = 0.0;
    QualityReport after;
    VariantRepair repair; //!< the untangling of its new invalid cells, if it had any
    //! The checks the variant fails that the set-up's mesh passed (on the master), each
    //! warned about by DesignStudy::warn_new_check_failures().
    morph::NewCheckFailures new_failed_checks;
    //! Refused for invalid cells: the patches they touch (morph/invalid_cells_location.h).
    std::vector<morph::PatchCells> invalid_cells_by_patch;
    bool refused = false;
    std::string refusal;
    std::string back_off; //!< refused: the variable whose removal repairs most
    bool written = false;
    std::string output_instance;
    std::filesystem::path points_file;
    double combine_seconds = 0.0, check_seconds = 0.0, write_seconds = 0.0;
};

//! Where a variant misses its prescriptions: at every point some variable constrains,
//! sum_j a_j (F_j - P_j) over the variables that constrain it.
struct ConstraintMisfit
{
    Points error;                  //!< nPoints x 3 (zero where nothing is constrained)
    std::vector<char> constrained; //!< per point: constrained by some variable
};

//! A case with its stored set-up, read once for any number of variants.
class DesignStudy
{
public:
    //! Reads the set-up header, then the mesh at the set-up's instance (unless options.time
    //! names one) and the morphDict, and refuses a stale set-up.
    //! \throw IoError, ParseError, InvalidInput (stale set-up, no designVariables).
    explicit DesignStudy(const morph::MorphOptions& options);
    ~DesignStudy();
    DesignStudy(const DesignStudy&) = delete;
    DesignStudy& operator=(const DesignStudy&) = delete;

    const DesignCase& design_case() const { return case_; }
    const std::filesystem::path& basis_file() const { return reader_->path(); }
    const DesignBasisHeader& header() const { return reader_->header(); }
    const std::vector<std::string>& names() const { return reader_->header().names; }
    double read_seconds() const { return read_seconds_; }

    //! \brief Check amplitudes against the variables' count and bounds.
    //! \throw InvalidInput naming the variable.
    void check_amplitudes(const std::vector<double>& a) const;
    //! \brief Build, check and (unless refused, or with force) write one variant to
    //! `instance` (the mesh's own with -overwrite): evaluate, then write.
    VariantResult apply(const std::vector<double>& amplitudes, const std::string& instance);
    //! \brief Build and check one variant in memory (points(): its points). New invalid
    //! cells are untangled (r.repair; unless morphDict `untangle no`) and the variant checked
    //! again; r.refused when some remain (unless force), and then, if search_back_off,
    //! r.back_off names the variable whose removal repairs most (one check per variable,
    //! without untangling). Writes nothing.
    VariantResult evaluate(const std::vector<double>& amplitudes, bool search_back_off = true);
    //! A warning per check r fails that the set-up's mesh passed (r.new_failed_checks).
    void warn_new_check_failures(const VariantResult& r) const;
    //! \brief Whether variant a has no more negative-volume cells or wrongly oriented face
    //! pyramids than x0: the two checks alone, for line searches (points() then holds it).
    //! The linear combination's verdict: no untangling (evaluate may still repair it).
    bool is_valid(const std::vector<double>& amplitudes);
    //! \brief Write the points of the last evaluated variant to `instance`, atomically.
    void write(VariantResult& r, const std::string& instance);
    //! The points of the last evaluated variant (the set-up's before the first).
    const Points& points() const { return case_.foam.mesh.points; }
    //! The set-up's points x0.
    const Points& initial_points() const { return x0_; }
    //! The cells' faces of the study's mesh (meshmorph::cell_faces), computed once.
    const CompactList& faces_of_cells() const { return cell_faces_; }
    //! The instance after `instance` (the next time), for a new variant.
    std::string next_instance(const std::string& instance) const;

    //! sum_j a_j F_j (nPoints x 3) and, if asked, its misfit at the constrained points. With
    //! a shared set-up: the shared fit applied to sum_j a_j P_j (shared_design_fit.h).
    Points combine(const std::vector<double>& a, ConstraintMisfit* misfit = nullptr);
    //! sum_i g_i . F_j(i) for every variable j (g: nPoints x 3); with -parallel summed over
    //! the ranks, each point once (a collective).
    std::vector<double> transpose_product(const Points& g);

    //! Whether the set-up is shared (one fit for every variable) rather than fields.
    bool shared() const { return shared_ != nullptr; }

private:
    //! combine() into `sum` (its storage kept when it has the size).
    void combine_into(const std::vector<double>& a, Points& sum,
                      ConstraintMisfit* misfit = nullptr);
    //! The row buffers at their size, before the set-up's check: a variant then reuses
    //! them, and the check's arrays reuse the set-up check's memory (fresh pages are what
    //! made the first variant 1.6x slower than the next on the motorBike).
    void reserve_row_buffers();
    //! The shared fit chosen again (a shared set-up): its constraints from the morphDict,
    //! each variable's prescription from the file.
    void load_shared_fit();
    //! The shared fit applied to `prescription`, on the set-up's points.
    Points apply_shared(const Points& prescription);
    Eigen::VectorXd ownership_weights() const;
    void measure_misfit(const Points& d, const ConstraintMisfit& misfit, VariantResult& r) const;
    //! Whether counts (or a report's) are higher than the set-up mesh's.
    bool has_new_invalid_cells(const InvalidCells& invalid) const;
    bool has_new_invalid_cells(const QualityReport& report) const;
    //! Whether the variant's new invalid cells are few enough for the local repair (at most
    //! max_untangled_fraction of the cells); if not, r.repair.skipped says so.
    bool worth_untangling(VariantResult& r) const;
    //! Untangle the variant in the study's mesh (morphDict `untangle`, as a one-off morph
    //! does) and check it again; `geometry` is the variant's on entry.
    void repair_variant(VariantResult& r, MeshGeometry& geometry);
    //! Per point, 1 when some design variable prescribes it (read from the set-up once).
    std::vector<char> prescribed_points();
    //! Whether the variant in the study's mesh (`geometry` its geometry) is refused (new
    //! invalid cells, no force).
    bool refuse(const std::vector<double>& amplitudes, const MeshGeometry& geometry,
                VariantResult& r, bool search_back_off);
    //! r.new_failed_checks, and with morphDict `newCheckFailures refuse` the refusal.
    void judge_new_check_failures(VariantResult& r);
    std::string back_off(const Points& moved, const std::vector<double>& a, Index invalid);

    //! The check of the variant in the study's mesh. Without per-cell fields (a variant's
    //! report is its summary), and with the topology part and the scaled Jacobian's corners
    //! of the set-up mesh's check (setup_report_): a variant moves points only.
    QualityReport check_variant(const MeshGeometry& geometry);

    morph::MorphOptions options_;
    std::optional<DesignBasisReader> reader_;
    DesignCase case_;
    CompactList cell_faces_;
    //! The check of the set-up's mesh, made when the study opens (collective; empty only
    //! while it is made): the topology part and corners every variant's check reuses
    //! (check_variant), and the failures a variant's are compared with.
    std::optional<QualityReport> setup_report_;
    Points x0_; //!< the set-up's points (the study's mesh holds the last variant's)
    std::optional<VariantRepairer> repairer_; //!< made when a variant first needs it
    std::unique_ptr<SharedDesignFit> shared_; //!< a shared set-up's fit (else null)
    double read_seconds_ = 0.0;
    //! A variant's displacement, misfit and variable block, reused from row to row.
    struct RowBuffers
    {
        Points sum;
        ConstraintMisfit misfit;
        VariableBlock block;
    } row_buffers_;
};

} // namespace meshmorph::design
