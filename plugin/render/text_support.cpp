#include "plugin/render/text_support.h"

#include <QGuiApplication>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrcloth::render {

void require_gui_application(const char* who) {
  if (qobject_cast<QGuiApplication*>(QCoreApplication::instance()) == nullptr)
    throw std::logic_error(std::string(who) +
                           ": drawing text needs a QGuiApplication (headless: QT_QPA_PLATFORM=offscreen)");
}

QFont make_font(int pixel_size, bool bold) {
  QFont font(QStringLiteral("DejaVu Sans"));
  font.setPixelSize(std::max(1, pixel_size));
  font.setBold(bold);
  return font;
}

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 0.0;
    hi = 1.0;
  }
  if (lo > hi) std::swap(lo, hi);
  const double scale = std::max(std::abs(lo), std::abs(hi));
  if (hi - lo <= 1e-12 * std::max(scale, 1e-300)) {
    const double widen = scale > 0 ? 0.1 * scale : 1.0;
    lo -= widen;
    hi += widen;
  }
  const double raw = (hi - lo) / std::max(1, target_count);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / magnitude;
  const double step = (r < 1.5 ? 1.0 : r < 3.0 ? 2.0 : r < 7.0 ? 5.0 : 10.0) * magnitude;
  // Snap values within rounding of a tick onto it, so 0.3 / 0.1 is 3, not 2.9999.
  auto snap = [](double k, double (*round_to)(double)) {
    return std::abs(k - std::round(k)) < 1e-9 ? std::round(k) : round_to(k);
  };
  const double first = snap(lo / step, std::floor);
  const double last = snap(hi / step, std::ceil);
  // At the ends of what a double holds the round ticks do not exist: a last
  // tick past 1.8e308 is infinite, a step of denormals (1e-323) underflows
  // to 0. Then the data's own ends are the ticks (the chart drew nothing).
  if (!(step >= std::numeric_limits<double>::min()) || !std::isfinite(first * step) ||
      !std::isfinite((last + 1.0) * step) || !(lo < hi))
    return lo < hi && std::isfinite(hi - lo) ? std::vector<double>{lo, hi} : std::vector<double>{0.0, 1.0};
  std::vector<double> ticks;
  for (double k = first; k <= last && ticks.size() < 1000; k += 1.0) {
    const double v = k * step;  // from the index, so no error accumulates
    ticks.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  }
  if (ticks.size() < 2) ticks = {first * step, (first + 1) * step};
  return ticks;
}

QString format_tick(double value, double step) {
  if (!std::isfinite(value)) return QStringLiteral("-");
  step = std::abs(step);
  if (!(step > 0) || !std::isfinite(step)) return QString::number(value, 'g', 4);
  if (std::abs(value) < 1e-6 * step) return QStringLiteral("0");
  if (std::abs(value) >= 1e7 || step < 1e-6) return QString::number(value, 'g', 4);
  const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 6);
  return QString::number(value, 'f', decimals);
}

}  // namespace mrcloth::render
