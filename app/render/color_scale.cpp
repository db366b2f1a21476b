#include "app/render/color_scale.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace dynamesh {

FieldStats field_stats(const std::vector<float>& values) {
  FieldStats s;
  std::vector<float> v;
  v.reserve(values.size());
  for (float x : values) {
    if (std::isfinite(x)) v.push_back(x);
  }
  if (v.empty()) return s;
  s.present = true;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  s.min = *lo;
  s.max = *hi;
  const auto at = [&v](double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
  };
  s.low = at(0.02);
  s.high = at(0.98);
  double sum = 0.0;
  for (float x : v) sum += x;
  s.mean = static_cast<float>(sum / static_cast<double>(v.size()));
  s.count = v.size();
  return s;
}

FieldStats merge(const FieldStats& a, const FieldStats& b) {
  if (!a.present) return b;
  if (!b.present) return a;
  FieldStats m;
  m.present = true;
  m.min = std::min(a.min, b.min);
  m.max = std::max(a.max, b.max);
  m.low = std::min(a.low, b.low);
  m.high = std::max(a.high, b.high);
  m.count = a.count + b.count;
  const double wa = static_cast<double>(a.count), wb = static_cast<double>(b.count);
  m.mean = m.count > 0 ? static_cast<float>((wa * a.mean + wb * b.mean) / (wa + wb))
                       : 0.5f * (a.mean + b.mean);
  return m;
}

void parse_color_range(const std::string& text, ColorSettings& into) {
  if (text == "frame" || text == "first" || text == "run") {
    into.range = text == "frame"   ? ColorRange::kFrame
                 : text == "first" ? ColorRange::kFirstFrame
                                   : ColorRange::kRun;
    return;
  }
  const auto comma = text.find(',');
  double lo = 0.0, hi = 0.0;
  std::size_t used_lo = 0, used_hi = 0;
  try {
    if (comma != std::string::npos) {
      lo = std::stod(text.substr(0, comma), &used_lo);
      hi = std::stod(text.substr(comma + 1), &used_hi);
    }
  } catch (const std::exception&) {
    used_lo = used_hi = 0;
  }
  if (comma == std::string::npos || used_lo != comma || used_hi != text.size() - comma - 1 ||
      !std::isfinite(lo) || !std::isfinite(hi))
    throw std::invalid_argument("expects frame, first, run or MIN,MAX, got '" + text + "'");
  if (!(hi > lo)) throw std::invalid_argument("MIN,MAX needs MIN < MAX, got '" + text + "'");
  into.range = ColorRange::kFixed;
  into.range_min = lo;
  into.range_max = hi;
}

std::string color_range_text(const ColorSettings& settings) {
  switch (settings.range) {
    case ColorRange::kFrame:
      return "frame";
    case ColorRange::kFirstFrame:
      return "first";
    case ColorRange::kRun:
      return "run";
    case ColorRange::kFixed:
      break;
  }
  std::ostringstream out;
  out.precision(17);
  out << settings.range_min << ',' << settings.range_max;
  return out.str();
}

std::vector<int> discrete_labels(const ColorScale& scale, int max_labels) {
  // A typed range may be anything: the labels stay within a million either way.
  const auto whole = [](double v) { return static_cast<long>(std::clamp(v, -1e6, 1e6)); };
  const long first = whole(std::ceil(scale.min)), last = whole(std::floor(scale.max));
  const auto floor_div = [](long a, long b) { return a / b - (a % b != 0 && a < 0 ? 1 : 0); };
  const auto multiples = [&](long stride) {
    return floor_div(last, stride) - (-floor_div(-first, stride)) + 1;
  };
  max_labels = std::max(max_labels, 2);
  long stride = 1;
  for (long decade = 1; multiples(stride) > max_labels; decade *= 10)
    for (long step : {2, 5, 10}) {
      stride = step * decade;
      if (multiples(stride) <= max_labels) break;
    }
  std::vector<int> labels;
  for (long v = -floor_div(-first, stride) * stride; v <= last; v += stride)
    labels.push_back(static_cast<int>(v));
  return labels;
}

bool has_color_scale(ColorMode mode, const FieldStats& stats) {
  return mode != ColorMode::kShaded && mode != ColorMode::kRegion && stats.present;
}

namespace {

// A non-empty interval, so the shader never divides by zero.
ColorScale widen(ColorScale s) {
  if (!(s.max > s.min)) s.max = s.min + std::max(1e-6f, std::abs(s.min) * 1e-3f);
  return s;
}

// [low, high] grown about its middle to span at least kMinRelativeRange |mean|.
std::pair<float, float> data_range(float low, float high, const FieldStats& stats) {
  const float least = kMinRelativeRange * std::abs(stats.mean);
  if (high - low >= least) return {low, high};
  const float middle = 0.5f * (low + high);
  return {middle - 0.5f * least, middle + 0.5f * least};
}

ColorScale curvature_scale(const FieldStats& stats, const ColorSettings& settings) {
  ColorScale s;
  s.label = "curvature";
  if (settings.range == ColorRange::kFixed) {
    s.min = static_cast<float>(settings.range_min);
    s.max = static_cast<float>(settings.range_max);
    s.map = s.min < 0.0f && s.max > 0.0f ? ColormapId::kCoolWarm : ColormapId::kViridis;
    return s;
  }
  if (stats.low < 0.0f && stats.high > 0.0f) {
    // Signed: a diverging map centred on zero, so flat stays neutral.
    const float m = std::max(-stats.low, stats.high);
    s.map = ColormapId::kCoolWarm;
    s.min = -m;
    s.max = m;
  } else {
    s.map = ColormapId::kViridis;
    std::tie(s.min, s.max) = data_range(stats.low, stats.high, stats);
  }
  return s;
}

}  // namespace

ColorScale color_scale(ColorMode mode, const ColorSettings& settings, const FieldStats& stats) {
  ColorScale s;
  s.label = std::string(color_mode_label(mode));
  switch (mode) {
    case ColorMode::kShaded:
    case ColorMode::kRegion:  // categories from the atlas: no scale
      break;
    case ColorMode::kError:
      s.map = settings.error_viridis ? ColormapId::kViridis : ColormapId::kErrorYellowGreenRed;
      s.min = 0.0f;
      s.max = static_cast<float>(settings.threshold);
      break;
    case ColorMode::kCurvature:
      s = curvature_scale(stats, settings);
      break;
    case ColorMode::kValence:
      // Eight bins for valences 3..10 (split-born vertices stay within 4..8).
      s.map = ColormapId::kCategorical;
      s.min = 2.5f;
      s.max = 10.5f;
      s.discrete = true;
      break;
    case ColorMode::kLevel:
      // Whole levels, one bin each (as valence): level 0 .. the deepest.
      s.map = ColormapId::kViridis;
      s.min = -0.5f;
      s.max = std::max(1.0f, stats.max) + 0.5f;
      if (settings.range == ColorRange::kFixed) {
        s.min = static_cast<float>(settings.range_min);
        s.max = static_cast<float>(settings.range_max);
      }
      s.discrete = true;
      break;
    case ColorMode::kIntensity: {
      s.map = settings.intensity_viridis ? ColormapId::kViridis : ColormapId::kGray;
      const double window =
          settings.intensity_auto ? stats.high - stats.low : settings.intensity_window;
      const double level =
          settings.intensity_auto ? 0.5 * (stats.high + stats.low) : settings.intensity_level;
      s.min = static_cast<float>(level - 0.5 * window);
      s.max = static_cast<float>(level + 0.5 * window);
      if (settings.intensity_auto) std::tie(s.min, s.max) = data_range(s.min, s.max, stats);
      if (settings.range == ColorRange::kFixed) {
        s.min = static_cast<float>(settings.range_min);
        s.max = static_cast<float>(settings.range_max);
      }
      break;
    }
  }
  return widen(s);
}

}  // namespace dynamesh
