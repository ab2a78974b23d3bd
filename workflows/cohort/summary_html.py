"""cohort.html: the cohort table in report.html's style. The style is glint's one page style,
report/html/glint.css (report.html inlines the same file at build time), read from the source
tree or from the installed share/glint/report/html/glint.css: both lie two folders above this
file's folder. The page inlines it, so it keeps its look when moved."""
import html
import pathlib
import re

STYLE_PATH = pathlib.Path(__file__).resolve().parents[2] / "report" / "html" / "glint.css"

# What this page adds to the shared style: the figure scales with the window.
PAGE_STYLE = """main { padding: 4px 18px 18px; }
figure { margin: 10px 0; } figure img { max-width: 100%; height: auto; background: #fff; }"""

# Columns whose numbers are lengths in the pair's unit, to this power (cohort.py's table).
LENGTH_POWER = {"area": 2, "volume_lost": 3, "volume_gained": 3, "max_depth": 1, "max_height": 1, "fit_rms": 1}
FRACTIONS = ("coverage", "fit_inlier_fraction", "fit_overlap")
TEXT_COLUMNS = ("subject", "before", "after", "fit_termination", "unit")
SUPERSCRIPT = {"1": "", "2": "²", "3": "³"}


def shared_style():
    """glint.css's text. Raises FileNotFoundError naming where it was looked for."""
    if not STYLE_PATH.is_file():
        raise FileNotFoundError(f"glint's page style {STYLE_PATH} is missing: the cohort workflow needs the "
                                "report/html folder of the glint sources, or share/glint/report/html when installed")
    return STYLE_PATH.read_text()


def header_label(column, unit):
    """A column's heading with its unit: "area (mm²)", "fit rotation (°)", "coverage (fraction)".
    A name that already ends in a unit (area_mm2, max_depth_mm, fit_rotation_deg) shows it."""
    if column.endswith("_deg"):
        return f"{column[:-4].replace('_', ' ')} (°)"
    if unit:
        named = re.fullmatch(rf"(.+)_{re.escape(unit)}([123]?)", column)
        if named:
            return f"{named.group(1).replace('_', ' ')} ({unit}{SUPERSCRIPT[named.group(2) or '1']})"
    words = column.replace("_", " ")
    if column in LENGTH_POWER:
        return f"{words} ({unit or 'units'}{SUPERSCRIPT[str(LENGTH_POWER[column])]})"
    if column in FRACTIONS:
        return f"{words} (fraction)"
    return words


def _cell(value):
    if isinstance(value, float):
        return f"{value:.4g}"
    return html.escape("" if value is None else str(value))


def _links(row):
    if row.get("error"):
        log = f"logs/{html.escape(row['subject'])}/{html.escape(row['before'])}_to_{html.escape(row['after'])}.log"
        return f'<a href="{log}">glint log</a>'
    folder = pathlib.PurePosixPath(row["report"]).parent
    return " ".join(f'<a href="{folder}/{name}">{name}</a>'
                    for name in ("report.html", "report.json", "regions.csv", "atlas.vtp"))


def verdict(rows):
    """The banner's sentence: how many pairs changed, stayed and were refused."""
    refused = [r for r in rows if r.get("error")]
    done = [r for r in rows if not r.get("error")]
    changed = [r for r in done if (r.get("regions") or 0) > 0]
    parts = [f"{len(changed)} with regions", f"{len(done) - len(changed)} without"]
    if refused:
        parts.append(f"{len(refused)} refused")
    kind = "undecided" if refused else "damage" if changed else "clear"
    return f"{len(rows)} pair{'s' if len(rows) != 1 else ''}: " + ", ".join(parts), kind


def page(rows, columns, png_name):
    """The page's text."""
    shown = [c for c in columns if c not in ("report", "error")]
    unit = next((r.get("unit") for r in rows if r.get("unit")), "")
    cls = lambda c: ' class="text"' if c in TEXT_COLUMNS else ""  # noqa: E731
    head = "".join(f"<th{cls(c)}>{html.escape(header_label(c, unit))}</th>" for c in shown)
    head += '<th class="text">files</th><th class="text">error</th>'
    body = []
    for r in rows:
        cells = "".join(f"<td{cls(c)}>{_cell(r.get(c))}</td>" for c in shown)
        refused = ' class="refused"' if r.get("error") else ""
        body.append(f'<tr{refused}>{cells}<td class="text">{_links(r)}</td>'
                    f'<td class="text wrap">{_cell(r.get("error"))}</td></tr>')
    sentence, kind = verdict(rows)
    problems = "".join(f'<li class="severe">{html.escape(r["subject"])} {html.escape(str(r["before"]))} → '
                       f'{html.escape(str(r["after"]))}: glint refused the input: {_cell(r["error"])}</li>'
                       for r in rows if r.get("error"))
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1"><title>glint cohort</title>
<style>
{shared_style()}
{PAGE_STYLE}
</style>
</head><body>
<header><h1>glint cohort</h1>
<p id="subtitle">{len(rows)} pair(s) of consecutive time points, each swept by <code>glint sweep --register</code>
(zoom 0); lengths in {html.escape(unit or "the meshes' units")}.</p></header>
<section id="banner" class="{kind}"><p id="verdict">{html.escape(sentence)}</p><ul id="warnings">{problems}</ul></section>
<main>
<figure><img src="{html.escape(png_name)}" alt="volume and regions per pair"></figure>
<div class="table-scroll"><table id="cohort" class="data"><thead><tr>{head}</tr></thead>
<tbody>
{chr(10).join(body)}
</tbody></table></div>
</main></body></html>
"""


def write_html(rows, columns, html_path, png_name):
    """The table (units in its headings, scrolling in its box), the figure, and per pair links to
    its report, regions and atlas (to glint's log, for a pair it refused); written to a temporary
    name first."""
    text = page(rows, columns, png_name)
    html_path = pathlib.Path(html_path)
    tmp = html_path.with_name(html_path.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(html_path)
