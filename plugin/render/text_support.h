#pragma once
// Shared by everything here that draws text: fonts, tick values and the
// QGuiApplication check. Text needs a QGuiApplication because Qt's font
// database lives in it; without one Qt aborts the process, so the check
// turns that into an exception instead.
#include <QFont>
#include <QString>

#include <vector>

namespace mrcloth::render {

/// Throws std::logic_error mentioning `who` unless a QGuiApplication exists
/// (headless: set QT_QPA_PLATFORM=offscreen before constructing it).
void require_gui_application(const char* who);

/// DejaVu Sans (installed with the project's packages, so images look the
/// same everywhere) at `pixel_size` pixels.
QFont make_font(int pixel_size, bool bold = false);

/// "Nice" round values (1, 2 or 5 times a power of ten apart) covering
/// [lo, hi]: the first is <= lo, the last >= hi, about `target_count`
/// intervals (>= 1). Swaps reversed bounds; widens an empty range (lo == hi)
/// around its value; non-finite bounds give 0..1. Always at least 2 values.
std::vector<double> nice_ticks(double lo, double hi, int target_count = 5);

/// A tick value printed with as many decimals as the tick spacing `step`
/// needs ("0.25", "1500"), and exactly "0" for values that are zero up to
/// rounding.
QString format_tick(double value, double step);

}  // namespace mrcloth::render
