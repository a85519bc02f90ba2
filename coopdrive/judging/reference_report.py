"""`coopdrive score REC --reference REF --report DIR`: a page (DIR/index.html) with the figures' table and the
estimate's errors over time inside its own 2-sigma bounds (reference_plots.py)."""

from __future__ import annotations

import html
from pathlib import Path

from coopdrive.judging.consistency import CONSISTENT_TWO_SIGMA_SHARE
from coopdrive.judging.reference_plots import FIGURES, write_reference_figures
from coopdrive.judging.reference_score import ReferenceScore


def _cell(value) -> str:
    return "–" if value is None else f"{value:.3f}" if isinstance(value, float) else html.escape(str(value))


def _table(scores: list[ReferenceScore]) -> str:
    names = list(dict.fromkeys(name for score in scores for name in score.best_fit))
    head = "".join(f"<th>{html.escape(s.name)} best fit</th><th>{html.escape(s.name)} stamped</th>" for s in scores)
    offsets = "".join(f"<td>{s.offset_s:+.3f}</td><td>+0.000</td>" for s in scores)
    rows = "".join(f"<tr><td>{html.escape(name)}</td>"
                   + "".join(f"<td>{_cell(figures.get(name))}</td>" for s in scores for figures in (s.best_fit,
                                                                                                   s.stamped))
                   + "</tr>" for name in names)
    return (f"<table><tr><th>figure</th>{head}</tr><tr><td>time offset (s)</td>{offsets}</tr>{rows}</table>")


def write_reference_report(folder: Path, title: str, scores: list[ReferenceScore]) -> Path:
    """DIR/index.html and its figures (of the first score, the estimate, at its best-fit offset); the page's path."""
    folder.mkdir(parents=True, exist_ok=True)
    estimate = scores[0]
    figures = write_reference_figures(estimate.errors, folder) if estimate.errors is not None else []
    images = "".join(f'<figure><img src="{name}" alt="{html.escape(FIGURES[name])}">'
                     f"<figcaption>{html.escape(FIGURES[name])}</figcaption></figure>" for name in figures)
    page = (f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title></head><body>"
            f"<h1>{html.escape(title)}</h1>{_table(scores)}"
            f"<p>A consistent 2-D estimate holds the reference in its 2-sigma ellipse "
            f"{CONSISTENT_TWO_SIGMA_SHARE:.1%} of the time, with a mean NEES of 2. The figures below are the "
            f"estimate's at its best-fit offset ({estimate.offset_s:+.3f} s).</p>{images}</body></html>")
    path = folder / "index.html"
    path.write_text(page)
    return path
