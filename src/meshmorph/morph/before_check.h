// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The check of the mesh before a morph, run alongside the fit.
//!
//! The fit leaves a core idle for much of its time (the factor's BLAS calls, the sorting of
//! candidates run on one thread), and the check before the morph is only needed once the
//! first step has been evaluated. In a serial run the check therefore runs on a thread of
//! its own from the start; in a -parallel run it runs in place, because its reductions are
//! collective operations that must keep their order on every rank. Either way the report is
//! the same (the checks do not depend on the thread count). A morph reads its summary and
//! its topology, not its per-cell fields, which are dropped as soon as the check ends.
#pragma once

#include <filesystem>
#include <future>
#include <optional>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/quality/check_settings.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::morph
{

class BeforeCheck
{
public:
    //! Starts the check of `mesh`, whose points are in `mesh_dir` (named by the warning when
    //! the mesh fails checks). `mesh` and `cell_faces` are kept by reference until the
    //! check has ended (report(), or the destructor); the others are not kept.
    BeforeCheck(const PolyMesh& mesh, const CompactList& cell_faces,
                const CheckMeshSettings& settings, const Decomposition& decomposition,
                const std::filesystem::path& mesh_dir);
    //! A check already done (a session that keeps the report of its mesh).
    explicit BeforeCheck(QualityReport done) : report_(std::move(done)) {}
    //! Waits for the check to end (if it still runs) and joins it.
    ~BeforeCheck();
    BeforeCheck(const BeforeCheck&) = delete;
    BeforeCheck& operator=(const BeforeCheck&) = delete;

    //! The report, once it is there; the first call warns if the mesh fails checks (not for
    //! a check already done). \throw what the check threw.
    const QualityReport& report();
    //! The report, moved out (report() must not be called after this). \throw as report().
    QualityReport take_report();
    //! The invalid counts of the report (what a step may not make worse).
    InvalidCells invalid();
    //! Seconds the caller has waited in report() so far.
    double waited_seconds() const { return waited_; }

private:
    std::future<QualityReport> running_;
    std::optional<QualityReport> report_;
    std::filesystem::path mesh_dir_; //!< empty: no warning
    double waited_ = 0.0;
};

} // namespace meshmorph::morph
