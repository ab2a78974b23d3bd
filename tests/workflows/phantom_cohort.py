"""Cohorts of condyle phantoms for the Slurm tests and the throughput measurement: every subject
has two time points, the second re-tessellated, moved and (for some) damaged. Scans are made
once per kind and shared by the subjects of that kind (a manifest may name a file twice), so a
cohort of a hundred pairs takes seconds to make; each pair is still its own sweep."""
import pathlib
import subprocess

DENT = "dent:center=2,-1,8.8 radius=3 depth=0.6"    # on the condyle's top
BUMP = "bump:center=-5,0,7 radius=2.5 depth=0.5"    # on its side
# (file, glint phantom arguments) of the later time point of each kind of subject; the earlier
# one is always the plain icosphere condyle.
KINDS = (
    ("dent.ply", ["--scheme", "uv", "--resolution", "48", "--damage", DENT, "--pose", "4,-3,5,0.3,-0.2,0.1"]),
    ("same.ply", ["--scheme", "uv", "--resolution", "40", "--pose", "2,3,-2,0.1,0.2,-0.1"]),
    ("both.ply", ["--scheme", "ico", "--resolution", "5", "--damage", DENT, "--damage", BUMP,
                  "--pose", "-3,2,-4,-0.2,0.1,0.3"]),
)
# Small sweeps: a pair takes about a second of glint on two cores.
SMALL = ["size=64", "azimuth_step=60", "elevations=[-45,0,45]"]


def phantom(glint, path, *args):
    subprocess.run([glint, "--quiet", "phantom", "condyle", *args, "-o", str(path)], check=True)


def write_cohort(folder, glint, subjects, refused=()):
    """Scans and manifest.csv in `folder` for `subjects` subjects (S000, S001, …, kinds in turn)
    plus, for each name in `refused`, a subject whose second scan glint cannot read. Returns the
    manifest's path."""
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    phantom(glint, folder / "base.ply", "--scheme", "ico", "--resolution", "4")
    for name, args in KINDS[:subjects]:
        phantom(glint, folder / name, *args)
    # A PLY header promising three vertices, followed by none: glint's loader refuses it.
    (folder / "truncated.ply").write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                          "property float y\nproperty float z\nelement face 1\n"
                                          "property list uchar int vertex_indices\nend_header\n")
    lines = ["subject,timepoint,path"]
    for i in range(subjects):
        lines += [f"S{i:03d},0,base.ply", f"S{i:03d},1,{KINDS[i % len(KINDS)][0]}"]
    for name in refused:
        lines += [f"{name},0,base.ply", f"{name},1,truncated.ply"]
    manifest = folder / "manifest.csv"
    manifest.write_text("\n".join(lines) + "\n")
    return manifest
