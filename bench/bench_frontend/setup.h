#pragma once
// What bench_frontend runs: the scene classes (one line each in
// sceneClasses()), the camera resolutions, the segmentation modes, and the
// frames of the run.
//
// A scene class names the rig's scene kind (sim::sceneKindFromString); a
// class whose kind the rig does not have yet is listed in the report as
// missing and skipped, so a class the rig gains later is measured without
// touching this benchmark. Likewise a mode the front end does not know
// (parseSegmentationMode) is listed as missing.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/sensor_model.h"

namespace brick_pose
{
namespace frontend_bench
{
struct Options
{
  int frames = 200;
  std::uint64_t seed = 1;
  std::string mosd_dir;      ///< Empty: test/data/mosd_learn under the source tree.
  std::string mosd_catalogue;  ///< Empty: catalogue.yaml there.
  std::string box_catalogue;   ///< Empty: config/boxes.yaml under the source tree.
  bool skip_mosd = false;
  bool skip_rig = false;       ///< Only the real-scene rows (quick look at mOSD).
  bool verbose = false;      ///< Each false positive, false complete and miss on stderr.
  /// Complete faces keep the corners they were measured with
  /// (RoiFilterParams::place_on_catalogue_size off), to compare.
  bool measured_corners = false;
  /// For profiling: each rig frame's front end runs this many times more
  /// after the measured run, its answers unused, so that a profile of the
  /// run is mostly the front end rather than the rig's rendering. The
  /// tables are the measured runs' alone.
  int repeat = 0;
  /// Non-empty: writes <scene>_<mode>.png match overlays of the mOSD rows
  /// there, and with --only one per rig frame run.
  std::string overlay_dir;
  /// Non-empty: only these rig scene kinds, modes and resolutions are run
  /// (comma lists, e.g. --only touching_rows colour_free 1280x720), with the
  /// full run's frame seeds and names, so a cell of the table is replayed
  /// alone. The tables then cover only what ran.
  std::vector<std::string> only_kinds, only_modes, only_resolutions;
  /// Non-negative: only the rig frame of this number (the number in the
  /// verbose lines' "frame N"), to profile or picture one frame.
  int only_frame = -1;
};

/// Whether `name` is in `allowed` (an empty list allows every name).
bool allowedBy(const std::vector<std::string>& allowed, const std::string& name);

/// Throws nothing; prints usage and exits on bad arguments.
Options parseOptions(int argc, char** argv);

/// The catalogue a class's scenes are built from.
enum class ClassCatalogue
{
  kBricks,  ///< MBZIRC bricks, each with a plate colour (BrickCatalogue::mbzirc2020()).
  kBoxes,   ///< Plain cardboard boxes without one (config/boxes.yaml).
};

struct SceneClass
{
  std::string label;      ///< Report name, e.g. "touching rows".
  std::string rig_kind;   ///< sim::SceneKind name.
  /// The earlier benchmark's classes: their frames follow its sequence
  /// (two singles, one organised and one unorganised pile in four frames)
  /// at its distances (0.5-2 m) so that its figures are reproduced. Other
  /// classes get frames / 4 frames each, framed by the rig's defaults for
  /// their kind (SceneParams::defaultsFor).
  bool legacy = false;
  ClassCatalogue catalogue = ClassCatalogue::kBricks;
  /// sim::DepthModel name: "ideal" (the earlier rig) or "d4xx" (a real
  /// D4xx's smoothing, fattening, quantisation and misregistration).
  std::string depth_model = "ideal";
  std::optional<sim::SceneKind> kind;  ///< Resolved; empty when the rig lacks it.
};

/// The classes, kinds resolved against the rig.
std::vector<SceneClass> sceneClasses();

struct Resolution
{
  std::string label;  ///< "1280x720"
  PinholeCamera camera;
  bool legacy = false;  ///< The earlier benchmark's resolution.
};

/// The rig's D415 colour modes 1280x720, 848x480 and 640x480 (sim::d415ColourMode).
std::vector<Resolution> resolutions();

struct ModeSpec
{
  std::string name;                      ///< As parseSegmentationMode takes it.
  std::optional<SegmentationMode> mode;  ///< Empty when the front end lacks it.
  bool colour_free = false;
  /// The mode the JSON's colour_free_* figures come from when it is present.
  bool preferred_colour_free = false;
};

std::vector<ModeSpec> modes();

/// The colour-free mode the headline figures are taken from: the preferred
/// one when present, else the first colour-free one present; nullptr if none.
const ModeSpec* headlineColourFreeMode(const std::vector<ModeSpec>& modes);

/// Front-end parameters of `mode`. Colour-free modes get the scene's up
/// direction (a robot knows gravity from tf: without it a brick's long side
/// faces have the size of a top face; zero leaves it unset) and, when
/// known, the plane the pile stands on (`support_plane`, as the nodelet's
/// support_frame gives it; zero leaves it unset); hsv runs with its
/// defaults, as the earlier benchmark did. `measured_corners`: see Options.
FrontEndParams frontEndParamsFor(const ModeSpec& mode, const Eigen::Vector3d& up_in_camera,
                                 const Eigen::Vector4d& support_plane = Eigen::Vector4d::Zero(),
                                 bool measured_corners = false);

/// One frame of the run: which class, its seed and lighting.
struct FrameSpec
{
  std::size_t scene_class = 0;  ///< Index into sceneClasses().
  std::uint64_t seed = 0;
  sim::Lighting lighting = sim::Lighting::kNormal;
  bool legacy = false;          ///< Part of the earlier benchmark's sequence.
};

/// The legacy sequence (options.frames frames over the legacy classes),
/// then frames / 4 frames of every other class the rig has.
std::vector<FrameSpec> framePlan(const std::vector<SceneClass>& classes, const Options& options);

/// SceneParams of a class (see SceneClass::legacy).
sim::SceneParams sceneParamsFor(const SceneClass& scene_class);

/// The sensor model of a class's depth model, with `lighting`.
sim::SensorModel sensorFor(const SceneClass& scene_class, sim::Lighting lighting);

/// Why `mode` cannot run on `catalogue` ("" when it can): hsv needs a type
/// with a plate colour.
std::string modeNotApplicable(const ModeSpec& mode, const BrickCatalogue& catalogue);
}  // namespace frontend_bench
}  // namespace brick_pose
