#include "app/cli/run_options.h"

#include "app/render/color_scale.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/adapt/adapt_options_check.h"
#include "core/io/number_text.h"

namespace dynamesh {
namespace {

std::string format_number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// The option readers both programs share (core/io/number_text.h), refusing as a usage error.
template <class Read>
auto read_option(Read read) {
  try {
    return read();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

double parse_number(const std::string& option, const std::string& text) {
  return read_option([&] { return option_number(option, text); });
}

long parse_integer(const std::string& option, const std::string& text) {
  return static_cast<long>(read_option([&] {
    return option_whole_number(option, text, -kLargestWholeNumber, kLargestWholeNumber);
  }));
}

// A whole number in [lo, hi]: values beyond an int are refused, never wrapped.
int parse_int(const std::string& option, const std::string& text, long lo, long hi) {
  return static_cast<int>(read_option([&] { return option_whole_number(option, text, lo, hi); }));
}

// Large enough for any real use, small enough that nothing wraps or runs for days.
constexpr long kMaxImageSide = 16384;

using Setter =
    std::function<void(RunOptions&, const std::string& option, const std::string& value)>;

// Options that take a value.
const std::map<std::string, Setter>& valued_options() {
  static const std::map<std::string, Setter> table = {
      {"--scene", [](RunOptions& o, auto&, auto& v) { o.scene = v; }},
      {"--param",
       [](RunOptions& o, auto&, auto& v) {
         try {
           o.params.push_back(parse_parameter_override(v));
         } catch (const std::invalid_argument& e) {
           throw UsageError(e.what());
         }
       }},
      {"--t0",
       [](RunOptions& o, auto& k, auto& v) {
         o.t0 = parse_number(k, v);
         o.interval_given = true;
       }},
      {"--t1",
       [](RunOptions& o, auto& k, auto& v) {
         o.t1 = parse_number(k, v);
         o.interval_given = true;
       }},
      {"--keyframes",
       [](RunOptions& o, auto& k, auto& v) {
         o.keyframes.clear();
         std::size_t start = 0;
         for (std::size_t comma; start <= v.size(); start = comma + 1) {
           comma = std::min(v.find(',', start), v.size());
           o.keyframes.push_back(parse_number(k, v.substr(start, comma - start)));
         }
         if (o.keyframes.size() < 2)
           throw UsageError(k + " expects at least two times, e.g. 0,1,0");
       }},
      {"--camera",
       [](RunOptions& o, auto& k, auto& v) {
         try {
           o.camera = parse_camera_view(v);
         } catch (const std::invalid_argument& e) {
           throw UsageError(k + ": " + e.what());
         }
       }},
      {"--color-range",
       [](RunOptions& o, auto& k, auto& v) {
         try {
           parse_color_range(v, o.colors);
         } catch (const std::invalid_argument& e) {
           throw UsageError(k + ": " + e.what());
         }
       }},
      {"--intensity-map",
       [](RunOptions& o, auto& k, auto& v) {
         if (v != "gray" && v != "viridis") throw UsageError(k + " must be gray or viridis");
         o.colors.intensity_viridis = v == "viridis";
       }},
      {"--steps", [](RunOptions& o, auto& k, auto& v) { o.steps = parse_int(k, v, 0, kMaxSteps); }},
      {"--threshold",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.threshold = parse_number(k, v);
         o.threshold_given = true;
       }},
      {"--epsilon",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.epsilon = parse_number(k, v);
         o.epsilon_given = true;
       }},
      {"--density",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.density = parse_number(k, v);
         o.density_given = true;
       }},
      {"--sampling",
       [](RunOptions& o, auto&, auto& v) {
         if (v != "predictive" && v != "full")
           throw UsageError("--sampling must be predictive or full, got '" + v + "'");
         o.adapt.sampling = v == "full" ? Sampling::kFull : Sampling::kPredictive;
       }},
      {"--renumber",
       [](RunOptions& o, auto&, auto& v) {
         if (v != "on" && v != "off")
           throw UsageError("--renumber must be on or off, got '" + v + "'");
         o.adapt.renumber = v == "on";
       }},
      {"--topology-events",
       [](RunOptions& o, auto&, auto& v) {
         if (v != "on" && v != "off")
           throw UsageError("--topology-events must be on or off, got '" + v + "'");
         o.adapt.topology_events = v == "on";
       }},
      {"--k", [](RunOptions& o, auto& k, auto& v) { o.adapt.smoothing.k = parse_number(k, v); }},
      {"--smooth-iters",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.smoothing.iterations = parse_int(k, v, 0, kMaxSmoothIterations);
       }},
      {"--smooth-settled",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.smoothing.settled_offset = parse_number(k, v);
       }},
      {"--edge-length",
       [](RunOptions& o, auto& k, auto& v) { o.edge_length = parse_number(k, v); }},
      {"--max-triangles",
       [](RunOptions& o, auto& k, auto& v) {
         const long n = parse_integer(k, v);  // its floor: adapt_option_problem
         o.adapt.max_triangles = static_cast<std::size_t>(std::max(n, 0L));
       }},
      {"--max-samples",
       [](RunOptions& o, auto& k, auto& v) {
         const long n = parse_integer(k, v);
         if (n < 1000) throw UsageError("--max-samples must be at least 1000, got " + v);
         o.adapt.max_samples = static_cast<std::size_t>(n);
       }},
      {"--max-seconds",
       [](RunOptions& o, auto& k, auto& v) {
         o.max_seconds = parse_number(k, v);
         if (!(o.max_seconds > 0)) throw UsageError("--max-seconds must be positive, got " + v);
       }},
      {"--max-memory",
       [](RunOptions& o, auto& k, auto& v) {
         o.max_memory_mb = parse_number(k, v);
         if (!(o.max_memory_mb >= 64))
           throw UsageError("--max-memory must be at least 64 (MiB), got " + v);
       }},
      {"--seed",
       [](RunOptions& o, auto& k, auto& v) {
         const long n = parse_integer(k, v);
         if (n < 0) throw UsageError("--seed must not be negative");
         o.adapt.seed = static_cast<std::uint64_t>(n);
       }},
      {"--volume", [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("volume", v); }},
      {"--mask", [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("mask", v); }},
      {"--atlas", [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("atlas", v); }},
      {"--implicit",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("implicit", v); }},
      // --height is both the image height (DESIGN.md, --render) and the height-field formula
      // (expr): a bare whole number is the former. --size and --height-field are unambiguous.
      {"--height",
       [](RunOptions& o, auto& k, auto& v) {
         if (!v.empty() && v.find_first_not_of("0123456789") == std::string::npos)
           o.height = parse_int(k, v, 16, kMaxImageSide);
         else
           o.scene_text.emplace_back("height", v);
       }},
      {"--height-field",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("height", v); }},
      {"--size",
       [](RunOptions& o, auto& k, auto& v) {
         const auto x = v.find('x');
         if (x == std::string::npos) throw UsageError(k + " expects WIDTHxHEIGHT, e.g. 1920x1080");
         o.width = parse_int(k, v.substr(0, x), 16, kMaxImageSide);
         o.height = parse_int(k, v.substr(x + 1), 16, kMaxImageSide);
       }},
      {"--parametric",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("parametric", v); }},
      {"--bounds", [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("bounds", v); }},
      {"--domain", [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("domain", v); }},
      {"--periodic",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("periodic", v); }},
      {"--base-mesh",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("base-mesh", v); }},
      {"--stats", [](RunOptions& o, auto&, auto& v) { o.stats_path = v; }},
      {"--export-final", [](RunOptions& o, auto&, auto& v) { o.export_final_path = v; }},
      {"--export", [](RunOptions& o, auto&, auto& v) { o.export_dir = v; }},
      {"--export-every",
       [](RunOptions& o, auto& k, auto& v) { o.export_every = parse_int(k, v, 1, kMaxSteps); }},
      {"--render", [](RunOptions& o, auto&, auto& v) { o.render_dir = v; }},
      {"--width",
       [](RunOptions& o, auto& k, auto& v) { o.width = parse_int(k, v, 16, kMaxImageSide); }},
      {"--color", [](RunOptions& o, auto&, auto& v) { o.color = v; }},
      {"--smooth-weights",
       [](RunOptions& o, auto& k, auto& v) {
         if (v != "uniform" && v != "inverse-length")
           throw UsageError(k + " expects uniform or inverse-length, got '" + v + "'");
         o.adapt.smoothing.scale_invariant_weights = v == "inverse-length";
       }},
  };
  return table;
}

const std::map<std::string, std::function<void(RunOptions&)>>& flag_options() {
  static const std::map<std::string, std::function<void(RunOptions&)>> table = {
      {"--quiet", [](RunOptions& o) { o.quiet = true; }},
      {"--check", [](RunOptions& o) { o.check = true; }},
      {"--smooth-raw-curvature", [](RunOptions& o) { o.adapt.smoothing.raw_curvature = true; }},
      {"--no-smooth", [](RunOptions& o) { o.adapt.smoothing.enabled = false; }},
      {"--no-structural", [](RunOptions& o) { o.adapt.structural = false; }},
      {"--no-geometric", [](RunOptions& o) { o.adapt.geometric = false; }},
      {"--wireframe", [](RunOptions& o) { o.wireframe = true; }},
      {"--no-wireframe", [](RunOptions& o) { o.wireframe = false; }},
  };
  return table;
}

void validate(RunOptions& o) {
  const AdaptOptions& a = o.adapt;
  // Each adaptation option's own range (shared with the viewer); the epsilon against a given T
  // here, against the scene's T in apply_scene_defaults.
  if (const std::string problem = adapt_option_problem(a); !problem.empty())
    throw UsageError(problem);
  if (o.threshold_given && o.epsilon_given && o.adapt.epsilon >= a.threshold)
    throw UsageError("--epsilon " + format_number(o.adapt.epsilon) + " must be below --threshold " +
                     format_number(a.threshold) + ": the weld bound T - eps must stay positive");
  if (!o.keyframes.empty() && o.interval_given)
    throw UsageError("--keyframes replaces --t0 and --t1: give one or the other");
  for (double t : o.keyframes)
    if (t < 0 || t > 1) throw UsageError("--keyframes: every time must lie in [0, 1]");
  if (o.keyframes.empty()) o.keyframes = {o.t0, o.t1};
  if (o.steps < 0) throw UsageError("--steps must not be negative (0 adapts once at --t0)");
  if (o.edge_length < 0) throw UsageError("--edge-length must be positive");
  if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
    throw UsageError("--width and --height must be between 16 and 16384 pixels");
  if (!parse_color_mode(o.color))
    throw UsageError(
        "--color must be one of error, curvature, intensity, region, valence, level, shaded");
}

}  // namespace

void apply_scene_defaults(RunOptions& o, const SceneInfo& scene) {
  if (!o.threshold_given) o.adapt.threshold = scene.suggested_threshold;
  if (!o.density_given) o.adapt.density = scene.suggested_density;
  if (!o.epsilon_given) o.adapt.epsilon = 0.25 * o.adapt.threshold;
  if (o.adapt.epsilon >= o.adapt.threshold) {
    const std::string which = o.threshold_given ? "--threshold " + format_number(o.adapt.threshold)
                                                : "the threshold of scene " + scene.name + ", " +
                                                      format_number(o.adapt.threshold);
    throw UsageError("--epsilon " + format_number(o.adapt.epsilon) + " must be below " + which +
                     ": the weld bound T - eps must stay positive");
  }
}

RunOptions parse_run_options(const std::vector<std::string>& args) {
  RunOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& word = args[i];
    if (const auto flag = flag_options().find(word); flag != flag_options().end()) {
      flag->second(o);
      continue;
    }
    const auto opt = valued_options().find(word);
    if (opt == valued_options().end())
      throw UsageError("unknown option '" + word + "' (see dynamesh-cli run --help)");
    if (i + 1 >= args.size()) throw UsageError(word + " needs a value");
    if (args[i + 1].empty()) throw UsageError(word + " needs a value, got an empty string");
    opt->second(o, word, args[++i]);
  }
  validate(o);
  return o;
}

std::string main_help() {
  return R"(dynamesh-cli — adapt a dynamic 4-8 mesh to a deforming surface, in batch

Usage:
  dynamesh-cli run [options]     run a scene over time; see 'dynamesh-cli run --help'
  dynamesh-cli scenes            list the scenes and their parameters
  dynamesh-cli --help            this text
  dynamesh-cli --version         the version, and the threads and OpenMP wait policy
                                 a run would use (OMP_NUM_THREADS sets the threads)

Example:
  dynamesh-cli run --scene sinc --steps 100 --threshold 0.004 --stats sinc.csv \
      --export-final sinc.ply
)";
}

std::string run_help() {
  return R"(Usage: dynamesh-cli run --scene NAME [options]

Adapts the scene's base mesh to S(t0), then takes N steps to t1, keeping every sampled
error within T + eps with few triangles (de Goes et al. 2006). Progress goes to stderr;
the last line of stdout is a JSON summary: the last step's triangles, vertices,
max_sample_error, mean_sample_error; over the run splits, welds, seconds_per_step
(median), peak_triangles, worst_max_sample_error (and their steps), keyframe_triangles,
resident_mb and peak_resident_mb (the process's memory at the end and at its peak); the
final mesh's valence_min, valence_max, min_angle_deg, ... Bad input: one line on
stderr, exit status 2, and none of the run's output files.

Scene:
  --scene NAME           sphere | capsule-bend | sinc | twist | mri | expr  [capsule-bend]
  --param KEY=VALUE      set a scene parameter (repeatable; 'dynamesh-cli scenes' lists them)
  --volume FILE|DIR      mri: a NIfTI volume (.nii or .nii.gz), a brain or a whole head
                         (the brain is then extracted), or a folder of one DICOM series
                         (converted with dcm2niix)
  --mask FILE            mri: a brain mask on the volume's grid (nonzero = brain, from BET,
                         SynthStrip, ...), used instead of the built-in segmentation
  --atlas FILE           mri: a label volume in the scan's space (names from FILE.nii.txt,
                         "index name" lines) for --color region; Colin27: AAL by default
  --implicit EXPR | --height-field EXPR | --parametric "X;Y;Z"   expr: a typed surface
                         (--height EXPR works too when EXPR is not a bare whole number)
  --bounds, --domain, --periodic, --base-mesh FILE          expr: its extent and base mesh
Time:
  --t0 T0 --t1 T1        animation interval [0, 1]  [0, 1]
  --keyframes T0,T1,...  visit these times in order instead (0,1,0: there and back)
  --steps N              N steps per interval (per keyframe segment); 0 adapts once at t0
                         [50]; step 0 is the initial adaptation, so N steps give N+1 rows
Adaptation:
  --threshold T          target geometric error, scene units  [the scene's: 0.008; mri 0.5 mm]
  --epsilon E            hysteresis: split above T+E, weld below T (README), 0 <= E < T  [T/4]
  --density D            samples per unit area, at least 9 per triangle  [the scene's: 2000;
                         mri 2 per mm^2]
  --edge-length L        target edge length (sphere: its x >= 0 half; elsewhere: a cap)
  --max-triangles M      refinement budget (reported when hit)  [2000000]
  --max-samples S        sample budget: refinement stops beyond S samples (reported)
                         [50000000]
  --max-seconds S        wall-time budget from the start (loading included; a load that
                         overruns it is refused): refinement and stepping stop after S seconds,
                         the run ends with what it has (reported)  [no limit]
  --max-memory MB        refused before starting when the budgets above could need more
                         memory than MB MiB (an estimate; mri: also its preprocessing, about
                         40 bytes per voxel)  [4096]
  --seed S               sample jitter seed  [1]
  --sampling MODE        predictive: re-measure only faces whose error may have left the
                         band since last measured; full: every face every step  [predictive]
  --renumber on|off      renumber the mesh along a Morton curve when its numbering has
                         scattered (memory locality: faster steps on large meshes; results
                         equal up to rounding; the stats column `renumbered`)  [on]
  --topology-events on|off
                         watch F for merges, splits, holes and pinches (surfaces whose
                         topology may change: expr, blobs, mri), report each and repair the
                         mesh; off: no events, and where the mesh's topology is no longer F's
                         its splits are held once the error stops falling  [on]
  --k K                  curvature sensitivity of the tangential smoothing  [2]
  --smooth-iters I       smoothing iterations per step  [1]
  --smooth-settled F     leave a vertex in place while it is within F of its ring's mean
                         edge from the ring's centroid (tangentially): it has settled, and
                         moving it would only chase Equation 1's fixed point by tiny moves;
                         0 moves every vertex every step, as the paper does  [0]
  --smooth-weights W     the one-ring centroid of Equation 1: uniform (the paper's) or
                         inverse-length (scale-invariant: keeps the 4-8 grading)  [uniform]
  --smooth-raw-curvature use raw curvature in Equation 1 (default: normalised to [0, 1])
  --no-smooth            no tangential smoothing
  --no-structural        no splits or welds (the mesh only moves)
  --no-geometric         no vertex correction: an ablation showing that splits and welds
                         alone cannot follow a moving surface; the run stops (status 2) at
                         the first step whose error exceeds T + eps
Output:
  --stats FILE.csv       one row per step (step 0 is the initial adaptation); - : stdout
  --export-final FILE    the final mesh (.ply binary with per-vertex error, or .obj)
  --export DIR           every --export-every K steps [1] a PLY and a VTK .vtp (with the
                         --color field), and DIR/frames.pvd: open it in ParaView to play them
  --render DIR           a PNG every --export-every K steps, rendered offscreen (no display
                         needed), --size WxH or --width W --height H  [1280x960]
  --color MODE           error | curvature | intensity (mri) | region (mri with an atlas) |
                         valence | level | shaded
                         [error: yellow = none, green, red = at or beyond T]
  --intensity-map M      intensity colours: gray or viridis (perceptual)  [gray]; the
                         window is the scan's 1st-99th percentile inside the brain
  --color-range R        what curvature, intensity and level colours span: frame (each
                         frame's own), first (the first frame's), run (the whole run's),
                         or MIN,MAX  [frame]
  --wireframe, --no-wireframe   draw the mesh's edges on the rendered frames  [drawn]
  --camera VIEW          fit, or AZIMUTH,ELEVATION[,DISTANCE]: degrees about +y and above
                         the ground plane (90: from above, -90: from below), distance from
                         the centre in scene units  [fit: 30,20, fitted]
  --check                verify the mesh invariants after every step (slow)
  --quiet                no progress lines
Files are written whole or not at all (a temporary name, then renamed); /dev/stdout, a
FIFO or - are written directly. A run stopped by Ctrl-C, SIGTERM, SIGHUP or SIGPIPE leaves
no partial file: frames already written stay, the CSV and the final mesh do not appear.
)";
}

}  // namespace dynamesh
