#include "text_painter.hpp"

#include <cairo-ft.h>
#include <cairo.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

namespace patchspin::render::internal {

namespace {

// One FreeType library for the process, never freed (cairo may keep font
// faces cached until exit).
FT_Library freetype() {
  static FT_Library library = [] {
    FT_Library lib = nullptr;
    if (FT_Init_FreeType(&lib) != 0) throw RenderError("FreeType initialisation failed");
    return lib;
  }();
  return library;
}

const cairo_user_data_key_t kFaceKey{};

cairo_font_face_t* loadFace(const std::string& file) {
  if (file.empty()) {
    throw RenderError(
        "no font file configured: install fonts-dejavu-core or set RenderOptions::fontFile");
  }
  FT_Face face = nullptr;
  {
    static std::mutex mutex;  // FT_New_Face is not thread-safe on a shared library
    std::lock_guard<std::mutex> lock(mutex);
    if (FT_New_Face(freetype(), file.c_str(), 0, &face) != 0) {
      throw RenderError("cannot load font " + file + " (install fonts-dejavu-core?)");
    }
  }
  cairo_font_face_t* cf = cairo_ft_font_face_create_for_ft_face(face, 0);
  // the FreeType face lives as long as cairo's font face
  cairo_font_face_set_user_data(cf, &kFaceKey, face,
                                [](void* f) { FT_Done_Face(static_cast<FT_Face>(f)); });
  return cf;
}

// "+0.123" / "-0.456" with a real minus sign; fixed width in a monospaced font.
std::string signedNumber(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v));
  const bool negative = v < 0.0 && std::string(buf).find_first_not_of("0.") != std::string::npos;
  return std::string(negative ? "\xe2\x88\x92" : "+") + buf;
}

struct Painter {
  cairo_t* cr;
  cairo_font_face_t* sans;
  cairo_font_face_t* mono;
  double size;

  void font(cairo_font_face_t* face, double scale) {
    cairo_set_font_face(cr, face);
    cairo_set_font_size(cr, size * scale);
  }
  double width(const std::string& s) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
  }
  void text(double x, double y, const std::string& s, Rgb c) {
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s.c_str());
  }
  void roundedBox(double x, double y, double w, double h, double radius, double alpha) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, x + w - radius, y + radius, radius, -M_PI / 2, 0);
    cairo_arc(cr, x + w - radius, y + h - radius, radius, 0, M_PI / 2);
    cairo_arc(cr, x + radius, y + h - radius, radius, M_PI / 2, M_PI);
    cairo_arc(cr, x + radius, y + radius, radius, M_PI, 3 * M_PI / 2);
    cairo_close_path(cr);
    cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, alpha);
    cairo_fill_preserve(cr);
    cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 0.25);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
  }
};

// One line of the info panel: optional colour swatch, then runs of text.
struct Run {
  std::string text;
  bool mono;
  Rgb colour;
};
struct Line {
  std::vector<Run> runs;
  bool swatch = false;
  Rgb swatchColour;
  double scale = 1.0;
};

// A framed chart in the bottom-right corner: axes box, the reference line,
// the series clipped to the box, the title and the axis ranges.
void drawChart(Painter& pt, const OverlayChart& chart, int w, int h, double fontPx) {
  cairo_t* cr = pt.cr;
  const double bw = std::round(0.34 * w), bh = std::round(0.3 * h);
  const double bx = w - bw - std::round(0.6 * fontPx), by = h - bh - std::round(0.6 * fontPx);
  pt.roundedBox(bx, by, bw, bh, 0.4 * fontPx, 0.82);
  // plot area inside the box
  const double px0 = bx + 2.6 * fontPx, px1 = bx + bw - 0.8 * fontPx;
  const double py0 = by + 1.7 * fontPx, py1 = by + bh - 1.5 * fontPx;
  if (px1 <= px0 || py1 <= py0) return;
  const double tSpan = chart.tMax > chart.tMin ? chart.tMax - chart.tMin : 1.0;
  const double ySpan = chart.yMax > chart.yMin ? chart.yMax - chart.yMin : 1.0;
  auto X = [&](double t) { return px0 + (t - chart.tMin) / tSpan * (px1 - px0); };
  auto Y = [&](double y) { return py1 - (y - chart.yMin) / ySpan * (py1 - py0); };
  const Rgb dark{0.08, 0.08, 0.1}, grey{0.35, 0.35, 0.4};
  // axes frame and range labels
  cairo_set_line_width(cr, 1.0);
  cairo_set_source_rgba(cr, 0, 0, 0, 0.45);
  cairo_rectangle(cr, px0, py0, px1 - px0, py1 - py0);
  cairo_stroke(cr);
  char buf[32];
  pt.font(pt.mono, 0.75);
  std::snprintf(buf, sizeof buf, "%.3g", chart.yMax);
  pt.text(px0 - pt.width(buf) - 0.25 * fontPx, py0 + 0.3 * fontPx, buf, grey);
  std::snprintf(buf, sizeof buf, "%.3g", chart.yMin);
  pt.text(px0 - pt.width(buf) - 0.25 * fontPx, py1, buf, grey);
  std::snprintf(buf, sizeof buf, "%.3g s", chart.tMin);
  pt.text(px0, py1 + 1.0 * fontPx, buf, grey);
  std::snprintf(buf, sizeof buf, "%.3g s", chart.tMax);
  pt.text(px1 - pt.width(buf), py1 + 1.0 * fontPx, buf, grey);
  pt.font(pt.sans, 0.85);
  pt.text(px0, by + 1.2 * fontPx, chart.title, dark);
  // everything below stays inside the plot area
  cairo_save(cr);
  cairo_rectangle(cr, px0, py0, px1 - px0, py1 - py0);
  cairo_clip(cr);
  cairo_set_line_width(cr, std::max(1.5, 0.18 * fontPx));
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const ChartSeries& s : chart.series) {
    bool drawing = false;
    for (std::size_t i = 0; i < s.t.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.t[i]) || !std::isfinite(s.y[i])) {
        drawing = false;
        continue;
      }
      // clamp far-out values so the path stays well defined
      const double y = std::clamp(s.y[i], chart.yMin - ySpan, chart.yMax + ySpan);
      if (drawing) {
        cairo_line_to(cr, X(s.t[i]), Y(y));
      } else {
        cairo_move_to(cr, X(s.t[i]), Y(y));
        drawing = true;
      }
    }
    cairo_set_source_rgb(cr, s.colour.r, s.colour.g, s.colour.b);
    cairo_stroke(cr);
  }
  if (chart.reference) {
    const double yr = Y(*chart.reference);
    const double dashes[] = {0.4 * fontPx, 0.3 * fontPx};
    cairo_set_dash(cr, dashes, 2, 0.0);
    cairo_set_source_rgba(cr, 0, 0, 0, 0.7);
    cairo_move_to(cr, px0, yr);
    cairo_line_to(cr, px1, yr);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0.0);
    if (!chart.referenceLabel.empty()) {
      // on a light patch so crossing series do not hide it
      pt.font(pt.mono, 0.75);
      const double lw = pt.width(chart.referenceLabel);
      const double lx = px1 - lw - 0.3 * fontPx, ly = yr - 0.3 * fontPx;
      cairo_rectangle(cr, lx - 0.15 * fontPx, ly - 0.7 * fontPx, lw + 0.3 * fontPx, 0.85 * fontPx);
      cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.85);
      cairo_fill(cr);
      pt.text(lx, ly, chart.referenceLabel, dark);
    }
  }
  cairo_restore(cr);
}

}  // namespace

TextPainter::TextPainter(const std::string& fontFile, const std::string& monoFontFile) {
  sans_ = loadFace(fontFile);
  try {
    mono_ = loadFace(monoFontFile.empty() ? fontFile : monoFontFile);
  } catch (...) {
    cairo_font_face_destroy(static_cast<cairo_font_face_t*>(sans_));
    throw;
  }
}

TextPainter::~TextPainter() {
  cairo_font_face_destroy(static_cast<cairo_font_face_t*>(sans_));
  cairo_font_face_destroy(static_cast<cairo_font_face_t*>(mono_));
}

void TextPainter::draw(Image& image, const FrameOverlay& overlay,
                       const std::vector<ScreenLabel>& labels, double fontPx) const {
  const int w = image.width, h = image.height;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  const int stride = cairo_image_surface_get_stride(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  // image -> cairo (native-endian 0x00RRGGBB words)
  cairo_surface_flush(surface);
  for (int y = 0; y < h; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      row[x] = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
    }
  }
  cairo_surface_mark_dirty(surface);

  cairo_t* cr = cairo_create(surface);
  // fixed font options so the output never depends on the environment
  cairo_font_options_t* fo = cairo_font_options_create();
  cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_SLIGHT);
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_ON);
  cairo_set_font_options(cr, fo);
  cairo_font_options_destroy(fo);

  Painter pt{cr, static_cast<cairo_font_face_t*>(sans_), static_cast<cairo_font_face_t*>(mono_),
             fontPx};
  const Rgb dark{0.08, 0.08, 0.1}, grey{0.3, 0.3, 0.35};

  // labels at projected points (under the panel)
  pt.font(pt.sans, 0.95);
  for (const ScreenLabel& label : labels) {
    if (label.text.empty()) continue;
    const double tw = pt.width(label.text);
    const double bw = tw + 0.8 * fontPx, bh = 1.3 * fontPx;
    double bx = label.above ? label.x - 0.5 * bw : label.x + 0.4 * fontPx;
    double by = label.above ? label.y - bh - 0.3 * fontPx : label.y - 0.5 * bh;
    bx = std::clamp(bx, 0.0, std::max(0.0, w - bw));
    by = std::clamp(by, 0.0, std::max(0.0, h - bh));
    pt.roundedBox(bx, by, bw, bh, 0.3 * fontPx, 0.7);
    pt.text(bx + 0.4 * fontPx, by + 0.5 * bh + 0.33 * fontPx, label.text, label.colour);
  }

  // info panel lines
  std::vector<Line> lines;
  if (!overlay.title.empty()) {
    Line line;
    line.runs = {{overlay.title, false, dark}};
    line.scale = 1.15;
    lines.push_back(line);
  }
  {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f s", overlay.time);
    Line line;
    line.runs = {{"t = ", false, grey}, {buf, true, dark}};
    if (!overlay.model.empty()) {
      line.runs.push_back({"    model: ", false, grey});
      line.runs.push_back({overlay.model, false, dark});
    }
    lines.push_back(line);
  }
  // label column width so the numbers line up
  double labelWidth = 0.0;
  pt.font(pt.sans, 1.0);
  for (const TrackedBody& b : overlay.tracked) labelWidth = std::max(labelWidth, pt.width(b.label));
  for (const TrackedBody& b : overlay.tracked) {
    Line line;
    line.swatch = true;
    line.swatchColour = b.colour;
    line.runs.push_back({b.label, false, dark});
    if (b.slipRatio) {
      line.runs.push_back({"  v/(R\xcf\x89) ", false, grey});
      char buf[32];
      std::snprintf(buf, sizeof buf, "%6.3f", *b.slipRatio);
      line.runs.push_back({buf, true, dark});
    }
    if (b.w) {
      line.runs.push_back({"  w ", false, grey});
      line.runs.push_back({"(" + signedNumber(b.w->x(), 2) + ", " + signedNumber(b.w->y(), 2) +
                               ", " + signedNumber(b.w->z(), 2) + ")",
                           true, dark});
    }
    lines.push_back(line);
  }

  // measure, then draw the panel
  const double pad = 0.5 * fontPx, lineHeight = 1.35 * fontPx, swatch = 0.8 * fontPx;
  double panelWidth = 0.0, panelHeight = 0.0;
  for (const Line& line : lines) {
    double x = line.swatch ? swatch + 0.5 * fontPx : 0.0;
    for (std::size_t i = 0; i < line.runs.size(); ++i) {
      pt.font(line.runs[i].mono ? pt.mono : pt.sans, line.scale);
      x += (line.swatch && i == 0) ? labelWidth : pt.width(line.runs[i].text);
    }
    panelWidth = std::max(panelWidth, x);
    panelHeight += lineHeight * line.scale;
  }
  const double x0 = std::round(0.6 * fontPx), y0 = std::round(0.6 * fontPx);
  pt.roundedBox(x0, y0, panelWidth + 2 * pad, panelHeight + 2 * pad, 0.4 * fontPx, 0.78);
  double y = y0 + pad;
  for (const Line& line : lines) {
    const double lh = lineHeight * line.scale;
    const double baseline = y + 0.5 * lh + 0.35 * fontPx * line.scale;
    double x = x0 + pad;
    if (line.swatch) {
      cairo_rectangle(cr, x, baseline - swatch, swatch, swatch);
      cairo_set_source_rgb(cr, line.swatchColour.r, line.swatchColour.g, line.swatchColour.b);
      cairo_fill_preserve(cr);
      cairo_set_source_rgba(cr, 0, 0, 0, 0.5);
      cairo_set_line_width(cr, 1.0);
      cairo_stroke(cr);
      x += swatch + 0.5 * fontPx;
    }
    for (std::size_t i = 0; i < line.runs.size(); ++i) {
      const Run& run = line.runs[i];
      pt.font(run.mono ? pt.mono : pt.sans, line.scale);
      pt.text(x, baseline, run.text, run.colour);
      x += (line.swatch && i == 0) ? labelWidth : pt.width(run.text);
    }
    y += lh;
  }

  // live chart, bottom right
  if (overlay.chart) drawChart(pt, *overlay.chart, w, h, fontPx);

  // caption, bottom centre
  if (!overlay.caption.empty()) {
    pt.font(pt.sans, 0.95);
    const double tw = pt.width(overlay.caption);
    const double bw = tw + 1.0 * fontPx, bh = 1.4 * fontPx;
    const double bx = 0.5 * (w - bw), by = h - bh - 0.5 * fontPx;
    pt.roundedBox(bx, by, bw, bh, 0.3 * fontPx, 0.75);
    pt.text(bx + 0.5 * fontPx, by + 0.5 * bh + 0.33 * fontPx, overlay.caption, dark);
  }

  cairo_destroy(cr);
  cairo_surface_flush(surface);
  // cairo -> image
  for (int yy = 0; yy < h; ++yy) {
    const auto* row =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(yy) * stride);
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.pixel(x, yy);
      p[0] = static_cast<std::uint8_t>(row[x] >> 16);
      p[1] = static_cast<std::uint8_t>(row[x] >> 8);
      p[2] = static_cast<std::uint8_t>(row[x]);
    }
  }
  cairo_surface_destroy(surface);
}

}  // namespace patchspin::render::internal
