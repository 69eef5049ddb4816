#pragma once
// Super4PCS on views of a whole object (ViewMode::kOn): a model of the whole
// surface of a cuboid (or of the faces a view may show), with normals,
// registered onto a scan from a known viewpoint that shows one to three of
// its faces.
//
// The scan is what all of lies on the model, so the 4-point bases are drawn
// from the scan (spanning two faces when it shows more than one) and their
// congruent sets looked for in the model, with normals (the scan's estimated
// and turned towards the viewpoint) filtering pairs and candidates. Candidates
// are ranked by the scan coverage with normals (view_consistency.h); the best
// distinct hypotheses, and the best one's near-symmetric alternatives
// (model_symmetry.h), each get a short point-to-plane fit and the full view
// check; the best is polished (icp_polish.h) and succeeds only if it passes
// the view acceptance with a margin (the confidence) over the best pose that
// is not the same up to a true symmetry of the model.
//
// The search is bounded by work (bases and candidates, deterministic for a
// seed) and by wall-clock time (a safety net that, when it cuts in, makes
// the result depend on the machine's load; the reason says so).

#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/registration_result.h"
#include "brick_pose/registration/super4pcs.h"

namespace brick_pose
{
namespace registration
{
/// Registers source (model frame) onto target (the scan, in the frame of
/// params.view.viewpoint_m). Source normals are used when given, else
/// estimated and turned outwards (a convex model). Inputs must have passed
/// validateRegistrationInput.
RegistrationResult alignWholeView(const PointSet& source, const PointSet& target, const Super4PCSParams& params);

/// Whether a source is a model of several faces rather than of one flat face
/// (what ViewMode::kAuto decides on): its normals, or else its points'
/// thickness, leave a plane.
bool isMultiFaceModel(const PointSet& source);
}  // namespace registration
}  // namespace brick_pose
