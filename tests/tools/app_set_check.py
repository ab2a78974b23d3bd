#!/usr/bin/env python3
"""Every file the app preset's configure and build read under /usr belongs to a Debian package in
the closure of tools/setup's app set (issue 51).

tools/demo installs the app set alone on a fresh machine; a package that configure or the build
touches but that only the test set installs (as openimageio-tools was: OpenImageIO's CMake
configuration checks that /usr/bin/iconvert exists) breaks the first command of every newcomer,
while CI and developers, who have the test set, never see it. This check maps what was really
read to the packages that own it:

  configure  an strace of `cmake --preset app` (every file syscall that succeeded);
  build      the commands ninja runs to build the `glint` target (compilers, include folders,
             libraries on the link lines, tools such as glslangValidator) and the headers the
             compiler read for its objects (ninja's deps log).

The closure is computed from dpkg's own database, as apt would resolve it on a minimal system:
the packages of priority required (what a minimal Debian 12 has), the app set, and, recursively,
their Depends and Pre-Depends (no Recommends: tools/setup installs with --no-install-recommends),
taking the first alternative that is installed and every installed provider of a virtual package.

Usage: app_set_check.py --packages FILE --configure-trace FILE [--app-dir DIR [--deps-dir DIR]]
                          [--ignore PATH...]
Exit 0 when every file is covered, 1 with one line per package outside the closure.
"""
import argparse
import glob
import os
import re
import subprocess
import sys

SYSTEM_PREFIXES = ("/usr/", "/lib/", "/lib64/", "/bin/", "/sbin/")
# note: Debian 12 is usr-merged: /lib, /bin and /sbin are links into /usr, and a package's file
# list may name either spelling, so both are looked up.
MERGED = ("/lib/", "/lib64/", "/bin/", "/sbin/")
# Read when present, done without when absent, whatever is built: glibc's locale aliases and
# message catalogues (every program that calls setlocale looks there under the caller's LANG).
ENVIRONMENT = ("/usr/share/locale/", "/usr/lib/locale/")


def parse_status(path="/var/lib/dpkg/status"):
    """Installed packages from dpkg's status file: name -> fields."""
    packages = {}
    with open(path, encoding="utf-8", errors="replace") as f:
        for stanza in f.read().split("\n\n"):
            fields, key = {}, None
            for line in stanza.splitlines():
                if line.startswith((" ", "\t")) and key:
                    fields[key] += "\n" + line
                elif ":" in line:
                    key, _, value = line.partition(":")
                    fields[key] = value.strip()
            name = fields.get("Package")
            if name and fields.get("Status", "").endswith(" installed"):
                packages[name] = fields
    return packages


def dependency_groups(fields):
    """[[alternative names], ...] of Depends and Pre-Depends, versions and arch qualifiers dropped."""
    groups = []
    for key in ("Pre-Depends", "Depends"):
        for group in filter(None, (g.strip() for g in fields.get(key, "").split(","))):
            groups.append([re.split(r"[\s(:]", alt.strip(), maxsplit=1)[0] for alt in group.split("|")])
    return groups


def closure(packages, roots):
    """Names apt would install for roots on a minimal system, resolved over what is installed."""
    providers = {}
    for name, fields in packages.items():
        for provided in filter(None, (p.strip() for p in fields.get("Provides", "").split(","))):
            providers.setdefault(re.split(r"[\s(:]", provided, maxsplit=1)[0], []).append(name)
    base = [n for n, f in packages.items()
            if f.get("Priority") == "required" or f.get("Essential") == "yes"]
    seen, todo, missing_roots = set(), list(base) + list(roots), []
    for root in roots:
        if root not in packages:
            missing_roots.append(root)
    while todo:
        name = todo.pop()
        if name in seen or name not in packages:
            continue
        seen.add(name)
        for alternatives in dependency_groups(packages[name]):
            chosen = next((a for a in alternatives if a in packages), None)
            if chosen:
                todo.append(chosen)
            else:
                for alt in alternatives:
                    todo.extend(providers.get(alt, []))
    return seen, missing_roots


def file_owners():
    """Path -> owning package, from dpkg's file lists."""
    owners = {}
    for listing in glob.glob("/var/lib/dpkg/info/*.list"):
        package = os.path.basename(listing)[: -len(".list")].split(":")[0]
        with open(listing, encoding="utf-8", errors="replace") as f:
            for line in f:
                owners.setdefault(line.rstrip("\n"), package)
    return owners


def owner_of(path, owners):
    candidates = [path, os.path.realpath(path)]
    for p in list(candidates):
        if p.startswith("/usr/") and p[4:].startswith(MERGED):
            candidates.append(p[4:])
        elif p.startswith(MERGED):
            candidates.append("/usr" + p)
    return next((owners[c] for c in candidates if c in owners), None)


TRACE_PATH = re.compile(r'^\d+\s+\w+\((?:AT_FDCWD, |\d+, )?"([^"]+)"')


def traced_files(trace):
    """Absolute system paths of regular files named by successful file syscalls in an strace log."""
    files = set()
    with open(trace, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = TRACE_PATH.match(line)
            if m and m.group(1).startswith(SYSTEM_PREFIXES) and not m.group(1).startswith(ENVIRONMENT):
                files.add(m.group(1))
    return {p for p in files if os.path.isfile(p)}


def build_files(app_dir, deps_dir, target):
    """System files the build of target reads: paths on its commands, and its objects' headers.

    app_dir is the configured (not built) app tree: its build.ninja holds the app's own commands.
    deps_dir is a built tree of the same sources (the test's own): ninja's deps log there says
    which headers the compiler read for the objects of the same targets (unity or file by file).
    """
    def ninja(build_dir, *tool):
        return subprocess.run(["ninja", "-C", build_dir, "-t", *tool], check=True,
                              capture_output=True, text=True).stdout

    commands = ninja(app_dir, "commands", target)
    files = set()
    link_dirs = {"/usr/lib/x86_64-linux-gnu", "/usr/lib"}
    libs = set()
    for token in re.findall(r"[^\s\"']+", commands):
        for prefix in ("-isystem", "-I", "-L", "-Wl,-rpath,", ""):
            if token.startswith(prefix) and token[len(prefix):].startswith(SYSTEM_PREFIXES):
                path = token[len(prefix):]
                if prefix == "-L":
                    link_dirs.add(path)
                if os.path.isfile(path):
                    files.add(path)
                break
        if token.startswith("-l") and len(token) > 2:
            libs.add(token[2:])
    for lib in libs:
        for d in sorted(link_dirs):
            found = [os.path.join(d, n) for n in (f"lib{lib}.so", f"lib{lib}.a")
                     if os.path.isfile(os.path.join(d, n))]
            if found:
                files.add(found[0])
                break
    # The target folders of every object the app builds for target ("mesh/CMakeFiles/glint_mesh.dir/").
    inputs = ninja(app_dir, "inputs", target).split()
    target_dirs = {re.sub(r"(\.dir/).*", r"\1", i) for i in inputs if i.endswith(".o") and ".dir/" in i}
    n_objects = 0
    if deps_dir:
        current = None
        for line in ninja(deps_dir, "deps").splitlines():
            if line and not line.startswith((" ", "\t")):
                obj = line.split(":")[0]
                current = any(obj.startswith(d) for d in target_dirs)
                n_objects += bool(current)
            elif current:
                path = line.strip()
                if path.startswith(SYSTEM_PREFIXES) and os.path.isfile(path):
                    files.add(path)
    return files, len(target_dirs), n_objects


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--packages", required=True, help="file: the app set, one package a line")
    ap.add_argument("--configure-trace", required=True, help="strace log of the app configure")
    ap.add_argument("--app-dir", help="the app preset's configured tree (its build commands)")
    ap.add_argument("--deps-dir", help="a built tree of the same sources (its headers read)")
    ap.add_argument("--target", default="glint")
    ap.add_argument("--ignore", nargs="*", default=[],
                    help="paths not part of the build (a compiler launcher such as ccache)")
    args = ap.parse_args()

    with open(args.packages, encoding="utf-8") as f:
        app = [line.strip() for line in f if line.strip() and not line.startswith("#")]
    packages = parse_status()
    covered, missing_roots = closure(packages, app)
    if missing_roots:
        print("FAIL: app set packages not installed here, cannot check: " + " ".join(missing_roots))
        return 1
    owners = file_owners()

    read = {p: "configure" for p in traced_files(args.configure_trace)}
    n_targets = n_objects = 0
    if args.app_dir:
        built, n_targets, n_objects = build_files(args.app_dir, args.deps_dir, args.target)
        for p in built:
            read.setdefault(p, "build")
    ignored = {os.path.realpath(p) for p in args.ignore if p}

    outside, unowned = {}, []
    for path, stage in sorted(read.items()):
        if os.path.realpath(path) in ignored:
            continue
        owner = owner_of(path, owners)
        if owner is None:
            unowned.append(path)
        elif owner not in covered:
            outside.setdefault((owner, stage), []).append(path)
    for (owner, stage), paths in sorted(outside.items()):
        shown = ", ".join(paths[:3]) + (f" and {len(paths) - 3} more" if len(paths) > 3 else "")
        print(f"FAIL: the app {stage} reads {shown} of package {owner}, which tools/setup's app set "
              f"does not install (add {owner} to app_packages)")
    print(f"app set: {len(app)} packages named, {len(covered)} in its closure (with the minimal "
          f"system); read by configure and build: {len(read)} system files"
          f" ({n_targets} targets, headers of {n_objects} objects), owned by "
          f"{len({owner_of(p, owners) for p in read} - {None})} packages; {len(unowned)} owned by "
          f"none (generated on the machine)")
    return 1 if outside else 0


if __name__ == "__main__":
    sys.exit(main())
