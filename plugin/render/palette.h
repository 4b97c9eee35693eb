#pragma once
// Colours shared by renders, legends and charts, so a mode or a series has
// the same colour in a preview and in its chart.
#include <QColor>

namespace mrcloth::render {

/// Distinct colours for categories (modes, series, refinement levels):
/// index 0.. cycles through 10 colours (Tableau 10). Negative indices wrap too.
QColor categorical_color(int index);

/// Perceptually even colour map for a value t in [0, 1] (clamped; NaN gives
/// grey): dark blue-violet at 0 through green to yellow at 1 (viridis).
QColor viridis(double t);

}  // namespace mrcloth::render
