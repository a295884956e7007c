#include "breastfit/render/colorbar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "breastfit/core/errors.h"
#include "breastfit/render/font.h"

namespace breastfit::render {

namespace {

void check_range(double lo, double hi) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
    throw InvalidInput("colour bar: need finite lo < hi, got lo=" + std::to_string(lo) +
                       " hi=" + std::to_string(hi));
}

double nice_step(double span, int target) {
  const double raw = span / std::max(1, target - 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / mag;
  const double nice = r < 1.5 ? 1.0 : r < 3.5 ? 2.0 : r < 7.5 ? 5.0 : 10.0;
  return nice * mag;
}

std::string title_of(const ColorbarSpec& spec) {
  if (spec.label.empty()) return spec.units;
  if (spec.units.empty()) return spec.label;
  return spec.label + " (" + spec.units + ")";
}

int max_label_width(const std::vector<double>& ticks, double step, int scale) {
  int w = 0;
  for (double t : ticks) w = std::max(w, text_size(format_tick(t, step), scale).width);
  return w;
}

double tick_step(const std::vector<double>& ticks, double lo, double hi) {
  return ticks.size() > 1 ? ticks[1] - ticks[0] : hi - lo;
}

}  // namespace

std::vector<double> colorbar_ticks(double lo, double hi, int target) {
  check_range(lo, hi);
  const double step = nice_step(hi - lo, std::max(2, target));
  std::vector<double> ticks;
  const double eps = 1e-9 * step;
  for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps; k += 1.0) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < eps ? 0.0 : v);
  }
  if (ticks.size() < 2) ticks = {lo, hi};
  return ticks;
}

std::string format_tick(double value, double step) {
  int decimals = 0;
  if (step > 0 && std::isfinite(step)) {
    decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
    // 2.5-type steps need one more decimal than their magnitude suggests.
    const double scaled = step * std::pow(10.0, decimals);
    if (std::abs(scaled - std::round(scaled)) > 1e-6) ++decimals;
  }
  decimals = std::min(decimals, 6);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  std::string s = buf;
  if (s == "-0" || s.find_first_not_of("-0.") == std::string::npos) {
    s = decimals > 0 ? "0." + std::string(static_cast<size_t>(decimals), '0') : "0";
  }
  return s;
}

ColorbarLayout colorbar_layout(const ColorbarSpec& spec, int bar_width, int bar_height, int text_scale) {
  check_range(spec.lo, spec.hi);
  const auto ticks = colorbar_ticks(spec.lo, spec.hi, spec.target_ticks);
  const int label_w = max_label_width(ticks, tick_step(ticks, spec.lo, spec.hi), text_scale);
  const TextSize title = text_size(title_of(spec), text_scale);
  const int tick_len = 3 * text_scale;
  const int width = std::max(bar_width + tick_len + 2 * text_scale + label_w, title.width);
  const int title_h = title.height > 0 ? title.height + 4 * text_scale : 0;
  const int height = title_h + bar_height + kGlyphHeight * text_scale / 2;
  return {width, height};
}

void draw_colorbar(Image& image, int x, int y, int bar_width, int bar_height, const ColorbarSpec& spec,
                   int text_scale, Rgb text_colour) {
  check_range(spec.lo, spec.hi);
  if (bar_width < 1 || bar_height < 2) throw InvalidInput("draw_colorbar: bar size must be positive");
  const std::string title = title_of(spec);
  int top = y;
  if (!title.empty()) {
    draw_text(image, x, y, title, text_colour, text_scale);
    top += text_size(title, text_scale).height + 4 * text_scale;
  }
  for (int row = 0; row < bar_height; ++row) {
    const double t = 1.0 - static_cast<double>(row) / (bar_height - 1);
    image.fill_rect(x, top + row, x + bar_width, top + row + 1, colormap_unit(spec.map, t));
  }
  const Rgb frame = {60, 60, 60};
  image.fill_rect(x - 1, top - 1, x + bar_width + 1, top, frame);
  image.fill_rect(x - 1, top + bar_height, x + bar_width + 1, top + bar_height + 1, frame);
  image.fill_rect(x - 1, top - 1, x, top + bar_height + 1, frame);
  image.fill_rect(x + bar_width, top - 1, x + bar_width + 1, top + bar_height + 1, frame);

  const auto ticks = colorbar_ticks(spec.lo, spec.hi, spec.target_ticks);
  const double step = tick_step(ticks, spec.lo, spec.hi);
  const int tick_len = 3 * text_scale;
  const int glyph_mid = (kGlyphHeight - 1) * text_scale / 2;
  for (double v : ticks) {
    const double t = (v - spec.lo) / (spec.hi - spec.lo);
    const int ty = top + static_cast<int>(std::lround((1.0 - t) * (bar_height - 1)));
    image.fill_rect(x + bar_width, ty - text_scale / 2, x + bar_width + tick_len,
                    ty - text_scale / 2 + std::max(1, text_scale / 2 + 1), frame);
    draw_text(image, x + bar_width + tick_len + 2 * text_scale, ty - glyph_mid + text_scale / 2,
              format_tick(v, step), text_colour, text_scale);
  }
}

}  // namespace breastfit::render
