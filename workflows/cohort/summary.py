"""The cohort summary: cohort.png (matplotlib, Debian's python3-matplotlib) and cohort.html
(the table with links to each pair's files; made by summary_html.py). Both are written to a
temporary name first."""
import pathlib

# One colour convention with every glint picture, atlas file and report.html: loss blue, gain
# red, the two ends of the diverging map (ColorBrewer RdBu, image/diverging_knots.h kDivergingKnots).
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


def write_html(rows, columns, html_path, png_name):
    """cohort.html, in report.html's style (summary_html.py)."""
    import summary_html  # beside this file, as the Snakefile imports this one

    summary_html.write_html(rows, columns, html_path, png_name)
