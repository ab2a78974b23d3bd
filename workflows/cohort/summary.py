"""The cohort summary: cohort.png (matplotlib, Debian's python3-matplotlib) and cohort.html
(the table with links to each pair's files). Both are written to a temporary name first."""
import html
import pathlib

# One colour convention with every glint picture, atlas file and report.html: loss blue, gain
# red, the two ends of the diverging map (ColorBrewer RdBu, report/detail/canvas.cpp kRdBu).
LOSS_COLOUR = "#2166ac"
GAIN_COLOUR = "#b2182b"


def write_png(rows, png_path):
    """Two panels per pair, grouped by subject: volume lost / gained, and regions found. A pair
    glint refused has no bars and "refused" under its name."""
    import matplotlib
    matplotlib.use("Agg")  # no display: files only
    import matplotlib.pyplot as plt

    labels = [f"{r['subject']}\n{r['before']}→{r['after']}" + ("\nrefused" if r.get("error") else "") for r in rows]
    x = range(len(rows))
    unit = next((r["unit"] for r in rows if r["unit"]), "")
    fig, (vol, reg) = plt.subplots(2, 1, figsize=(max(6.0, 1.1 * len(rows) + 2), 6.5), sharex=True)
    vol.bar([i - 0.2 for i in x], [r["volume_lost"] or 0 for r in rows], width=0.4, label="lost", color=LOSS_COLOUR)
    vol.bar([i + 0.2 for i in x], [r["volume_gained"] or 0 for r in rows], width=0.4, label="gained", color=GAIN_COLOUR)
    vol.set_ylabel(f"volume ({unit}³)" if unit else "volume (units³)")
    vol.legend(loc="upper right")
    vol.set_title("glint cohort: change between consecutive time points")
    reg.bar(x, [r["regions"] or 0 for r in rows], color="#4d4d4d")
    reg.set_ylabel("regions")
    reg.set_xticks(list(x))
    reg.set_xticklabels(labels, fontsize=8)
    reg.yaxis.get_major_locator().set_params(integer=True)
    fig.tight_layout()
    png_path = pathlib.Path(png_path)
    tmp = png_path.with_name(png_path.stem + ".tmp.png")
    fig.savefig(tmp, dpi=100)
    plt.close(fig)
    tmp.replace(png_path)


def _cell(value):
    if isinstance(value, float):
        return f"{value:.4g}"
    return html.escape("" if value is None else str(value))


def write_html(rows, columns, html_path, png_name):
    """The table, the figure, and per pair links to its report, regions and atlas (to glint's
    log, for a pair it refused)."""
    head = "".join(f"<th>{html.escape(c)}</th>" for c in columns if c not in ("report", "error"))
    head += "<th>files</th><th>error</th>"
    body = []
    for r in rows:
        cells = "".join(f"<td>{_cell(r[c])}</td>" for c in columns if c not in ("report", "error"))
        if r.get("error"):
            log = f"logs/{html.escape(r['subject'])}/{html.escape(r['before'])}_to_{html.escape(r['after'])}.log"
            links = f'<a href="{log}">glint log</a>'
        else:
            folder = pathlib.PurePosixPath(r["report"]).parent
            links = " ".join(f'<a href="{folder}/{name}">{name}</a>' for name in ("report.json", "regions.csv", "atlas.vtp"))
        body.append(f"<tr>{cells}<td>{links}</td><td style=\"text-align:left\">{_cell(r.get('error'))}</td></tr>")
    text = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>glint cohort</title>
<style>body{{font-family:sans-serif}} table{{border-collapse:collapse}} td,th{{border:1px solid #999;padding:2px 6px;text-align:right}}</style>
</head><body>
<h1>glint cohort</h1>
<p>{len(rows)} pair(s) of consecutive time points, each swept by <code>glint sweep --register</code> (zoom 0).</p>
<img src="{html.escape(png_name)}" alt="volume and regions per pair">
<table><tr>{head}</tr>
{chr(10).join(body)}
</table></body></html>
"""
    html_path = pathlib.Path(html_path)
    tmp = html_path.with_name(html_path.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(html_path)
