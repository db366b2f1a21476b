#include "app/cli/run_options.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>

namespace dynamesh {
namespace {

double parse_number(const std::string& option, const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value))
    throw UsageError(option + " expects a number, got '" + text + "'");
  return value;
}

long parse_integer(const std::string& option, const std::string& text) {
  const double value = parse_number(option, text);
  if (value != std::floor(value) || std::abs(value) > 9e15)
    throw UsageError(option + " expects a whole number, got '" + text + "'");
  return static_cast<long>(value);
}

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
      {"--t0", [](RunOptions& o, auto& k, auto& v) { o.t0 = parse_number(k, v); }},
      {"--t1", [](RunOptions& o, auto& k, auto& v) { o.t1 = parse_number(k, v); }},
      {"--steps",
       [](RunOptions& o, auto& k, auto& v) { o.steps = static_cast<int>(parse_integer(k, v)); }},
      {"--threshold",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.threshold = parse_number(k, v);
         o.threshold_given = true;  // else the scene's suggestion replaced it
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
      {"--k", [](RunOptions& o, auto& k, auto& v) { o.adapt.smoothing.k = parse_number(k, v); }},
      {"--smooth-iters",
       [](RunOptions& o, auto& k, auto& v) {
         o.adapt.smoothing.iterations = static_cast<int>(parse_integer(k, v));
       }},
      {"--edge-length",
       [](RunOptions& o, auto& k, auto& v) { o.edge_length = parse_number(k, v); }},
      {"--max-triangles",
       [](RunOptions& o, auto& k, auto& v) {
         const long n = parse_integer(k, v);
         if (n < 2) throw UsageError("--max-triangles must be at least 2, got " + v);
         o.adapt.max_triangles = static_cast<std::size_t>(n);
       }},
      {"--seed",
       [](RunOptions& o, auto& k, auto& v) {
         const long n = parse_integer(k, v);
         if (n < 0) throw UsageError("--seed must not be negative");
         o.adapt.seed = static_cast<std::uint64_t>(n);
       }},
      {"--volume", [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("volume", v); }},
      {"--implicit",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("implicit", v); }},
      // --height is both the image height (DESIGN.md, --render) and the height-field formula
      // (expr): a bare whole number is the former. --size and --height-field are unambiguous.
      {"--height",
       [](RunOptions& o, auto& k, auto& v) {
         if (!v.empty() && v.find_first_not_of("0123456789") == std::string::npos)
           o.height = static_cast<int>(parse_integer(k, v));
         else
           o.scene_text.emplace_back("height", v);
       }},
      {"--height-field",
       [](RunOptions& o, auto&, auto& v) { o.scene_text.emplace_back("height", v); }},
      {"--size",
       [](RunOptions& o, auto& k, auto& v) {
         const auto x = v.find('x');
         if (x == std::string::npos) throw UsageError(k + " expects WIDTHxHEIGHT, e.g. 1920x1080");
         o.width = static_cast<int>(parse_integer(k, v.substr(0, x)));
         o.height = static_cast<int>(parse_integer(k, v.substr(x + 1)));
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
       [](RunOptions& o, auto& k, auto& v) {
         o.export_every = static_cast<int>(parse_integer(k, v));
         if (o.export_every < 1) throw UsageError("--export-every must be at least 1");
       }},
      {"--render", [](RunOptions& o, auto&, auto& v) { o.render_dir = v; }},
      {"--width",
       [](RunOptions& o, auto& k, auto& v) { o.width = static_cast<int>(parse_integer(k, v)); }},
      {"--color", [](RunOptions& o, auto&, auto& v) { o.color = v; }},
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
  };
  return table;
}

void validate(RunOptions& o) {
  const AdaptOptions& a = o.adapt;
  if (!(a.threshold > 0)) throw UsageError("--threshold must be positive (try 0.008)");
  if (!o.epsilon_given) o.adapt.epsilon = 0.25 * a.threshold;
  if (o.adapt.epsilon < 0 || o.adapt.epsilon >= a.threshold)
    throw UsageError(
        "--epsilon must be in [0, threshold): the weld bound T - eps must stay positive");
  if (!(a.density > 0)) throw UsageError("--density must be positive (samples per unit area)");
  if (o.steps < 0) throw UsageError("--steps must not be negative (0 adapts once at --t0)");
  if (a.smoothing.iterations < 0) throw UsageError("--smooth-iters must not be negative");
  if (a.smoothing.k < 0) throw UsageError("--k must not be negative");
  if (o.edge_length < 0) throw UsageError("--edge-length must be positive");
  if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
    throw UsageError("--width and --height must be between 16 and 16384 pixels");
  const char* colors[] = {"error", "curvature", "intensity", "valence", "level", "shaded"};
  bool known = false;
  for (const char* c : colors) known = known || o.color == c;
  if (!known)
    throw UsageError("--color must be one of error, curvature, intensity, valence, level, shaded");
}

}  // namespace

void apply_scene_defaults(RunOptions& o, const SceneInfo& scene) {
  if (!o.threshold_given) o.adapt.threshold = scene.suggested_threshold;
  if (!o.density_given) o.adapt.density = scene.suggested_density;
  if (!o.epsilon_given) o.adapt.epsilon = 0.25 * o.adapt.threshold;
  if (o.adapt.epsilon >= o.adapt.threshold)
    throw UsageError("--epsilon must be below the threshold (" + std::to_string(o.adapt.threshold) +
                     " for scene " + scene.name + "): the weld bound T - eps must stay positive");
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

Example:
  dynamesh-cli run --scene sinc --steps 100 --threshold 0.004 --stats sinc.csv \
      --export-final sinc.ply
)";
}

std::string run_help() {
  return R"(Usage: dynamesh-cli run --scene NAME [options]

Adapts the scene's base mesh to S(t0), then takes N steps to t1, keeping every sampled
error within T + eps with few triangles (de Goes et al. 2006). Progress goes to stderr;
the last line of stdout is a JSON summary (triangles, vertices, max_sample_error,
mean_sample_error, splits, welds, seconds_per_step (median), valence_min, valence_max,
min_angle_deg, ...). Bad input: one line on stderr and exit status 2.

Scene:
  --scene NAME           sphere | capsule-bend | sinc | twist | mri | expr  [capsule-bend]
  --param KEY=VALUE      set a scene parameter (repeatable; 'dynamesh-cli scenes' lists them)
  --volume FILE          mri: a NIfTI brain volume (.nii or .nii.gz)
  --implicit EXPR | --height-field EXPR | --parametric "X;Y;Z"   expr: a typed surface
                         (--height EXPR works too when EXPR is not a bare whole number)
  --bounds, --domain, --periodic, --base-mesh FILE          expr: its extent and base mesh
Time:
  --t0 T0 --t1 T1        animation interval [0, 1]
  --steps N              N steps from t0 to t1; 0 adapts once at t0  [50]
Adaptation:
  --threshold T          target geometric error, scene units  [the scene's: 0.008; mri 0.5 mm]
  --epsilon E            hysteresis: weld below T-E, split above T+E, 0 <= E < T  [T/4]
  --density D            samples per unit area, at least 9 per triangle  [the scene's: 2000;
                         mri 2 per mm^2]
  --edge-length L        target edge length (sphere: its x >= 0 half; elsewhere: a cap)
  --max-triangles M      refinement budget (reported when hit)  [2000000]
  --seed S               sample jitter seed  [1]
  --sampling MODE        predictive: re-measure only faces whose error may have left the
                         band since last measured; full: every face every step  [predictive]
  --k K                  curvature sensitivity of the tangential smoothing  [2]
  --smooth-iters I       smoothing iterations per step  [1]
  --smooth-raw-curvature use raw curvature in Equation 1 (default: normalised to [0, 1])
  --no-smooth            no tangential smoothing
  --no-structural        no splits or welds (the mesh only moves)
  --no-geometric         no vertex correction (the mesh only refines)
Output:
  --stats FILE.csv       one row per step (step 0 is the initial adaptation)
  --export-final FILE    the final mesh (.ply binary with per-vertex error, or .obj)
  --export DIR           a PLY (with the --color field) every --export-every K steps  [1]
  --render DIR           a PNG every --export-every K steps, rendered offscreen (no display
                         needed), --size WxH or --width W --height H  [1280x960]
  --color MODE           error | curvature | intensity (mri) | valence | level | shaded
                         [error: yellow = none, green, red = at or beyond T]
  --check                verify the mesh invariants after every step (slow)
  --quiet                no progress lines
)";
}

}  // namespace dynamesh
