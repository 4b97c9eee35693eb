#pragma once
// The progress bar's line, fitted to the terminal: a line longer than the
// terminal wraps, and redrawing in place then erases only its last part, so
// each update left a line behind on an 80-column terminal.
#include <QString>

namespace mrcloth {

/// The bar's width when the terminal has room for it.
inline constexpr int kProgressBarWidth = 24;
/// Narrower than this, the bar says nothing and is left out.
inline constexpr int kLeastProgressBarWidth = 5;

/// "[job] <id>: [###.....] <figures>" (figures: "70/230 (30%), 2.41/s, ETA
/// 6.0 s"), at most `columns` - 1 characters long (the last column would
/// make some terminals wrap): the bar is narrowed first, down to
/// kLeastProgressBarWidth, then left out, then the text is cut at its end.
/// `fraction` is the part done, in [0, 1].
QString fitProgressBarLine(const QString& job_id, double fraction, const QString& figures, int columns);

/// The terminal's width in columns: of stderr's terminal, else $COLUMNS,
/// else 80.
int terminalColumns();

}  // namespace mrcloth
