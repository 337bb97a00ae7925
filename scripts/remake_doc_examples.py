#!/usr/bin/python3
"""Remakes the printouts and figures that the tutorials and how-to guides show.

    scripts/remake_doc_examples.py [PAGE.md ...] [--binary build/bkquake] [--keep DIR]
                                   [--check] [--long]

For each page (default: docs/tutorials/*.md and docs/how-to/*.md) that marks a printout or
a figure, runs the page's ```bash blocks in order, at the page's own sizes, in a scratch
folder holding data/, analysis/ and build/bkquake (the conventions of
tests/regression/test_tutorials.cpp), then

- rewrites each ```text block below `<!-- output of: COMMAND -->` from COMMAND's standard
  output: each shown line (the block may be an excerpt) is replaced by the first later line
  of the output with the same words (numbers aside); a shown line whose words the program no
  longer prints is reported and left for a person to edit;
- copies the file FILE that the blocks wrote over the image of the next `![...](IMG)` line
  below `<!-- figure: FILE -->`.

`<!-- remake SUBCOMMAND: OPTIONS -->` above a block appends OPTIONS to that block's
`build/bkquake SUBCOMMAND` commands here only (where the page shows a figure of a larger run
than its command, e.g. more seeds); the test's `<!-- test ...: -->` options are not applied.
With --check nothing is written: the script says which printouts and figures would change.

--long also remakes the how-to figures drawn from studies of 10^6 events per run (LONG
below: the Carlson-Langer scenes' b scan and window by eye in fit-window.md, the
Carlson-Langer sweep in sweeps.md and validation/carlson-langer.md): their commands run in
the same kind of scratch folder, and the figures they draw replace the pages' images. They
take several CPU-minutes (eight sweep points and two runs of 10^6 events), so the test
suite never runs them.
Nothing is written outside the pages and their images; the scratch folder is removed unless
--keep names one.
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

NUMBER = re.compile(r"[-+]?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?")
OUTPUT = re.compile(r"^<!-- output of: (.*\S)\s*-->\s*$")
FIGURE = re.compile(r"^<!-- figure: (\S+)\s*-->\s*$")
REMAKE = re.compile(r"^<!-- remake ([a-z-]+): (.*) -->\s*$")
IMAGE = re.compile(r"!\[[^\]]*\]\(([^)]+\.png)\)")
BKQUAKE = re.compile(r"^\s*build/bkquake\s+([a-z-]+)\b")


# The figures of the how-to pages drawn from studies too long for a page's own blocks: the
# pages they belong to, the commands that make them (run in order, as the pages give them)
# and each file those write -> the image it replaces (paths relative to the repository).
LONG = [
    {"pages": ["docs/how-to/fit-window.md"],
     "commands": [
         "build/bkquake run data/scenes/cl-l10-a1-n100.ini --out runs/cl/cl-l10-a1-n100 --quiet",
         "build/bkquake fit runs/cl/cl-l10-a1-n100 --scan > /dev/null",
         "/usr/bin/python3 analysis/plot_b_scan.py runs/cl/cl-l10-a1-n100",
         "build/bkquake run data/scenes/cl-l10-a2.5-n100.ini --out runs/cl/a2.5 --quiet",
         "/usr/bin/python3 analysis/plot_gr.py runs/cl/a2.5 --mu-min -7.6 --mu-max -2",
     ],
     "figures": {"runs/cl/cl-l10-a1-n100/b_scan.png": "docs/img/b_scan_cl_a1.png",
                 "runs/cl/a2.5/gr.png": "docs/img/gr_cl_a2.5_eye_window.png"}},
    {"pages": ["docs/how-to/sweeps.md", "docs/validation/carlson-langer.md"],
     "commands": [
         "build/bkquake sweep data/sweeps/carlson-langer-table.ini --out runs/cl-table > /dev/null",
         "build/bkquake fit runs/cl-table --mu-min -7.6 --mu-max -2 > /dev/null",
         "/usr/bin/python3 analysis/plot_sweep.py runs/cl-table --reference "
         "data/reference/carlson-langer-published.csv --out runs/cl-table/sweep_cl_table.png",
     ],
     "figures": {"runs/cl-table/sweep_cl_table.png": "docs/img/plots/sweep_cl_table.png"}},
]


def squeezed(text):
    return " ".join(text.split())


def words(line):
    """The line with each number as #, whitespace runs as one space (as the test compares)."""
    return squeezed(NUMBER.sub("#", line))


def parse(lines):
    """The page's bash blocks (first line, commands, remake options), shown printouts (the
    command, the text block's first and last content line, the bash blocks before it) and
    figures (the file, the image path, the bash blocks before it)."""
    blocks, shown, figures = [], [], []
    options, output, figure = {}, None, None
    i = 0
    while i < len(lines):
        line = lines[i]
        m_out, m_fig, m_opt = OUTPUT.match(line), FIGURE.match(line), REMAKE.match(line)
        if m_opt:
            options[m_opt.group(1)] = (options.get(m_opt.group(1), "") + " " + m_opt.group(2)).strip()
        elif m_out:
            output = m_out.group(1)
        elif m_fig:
            figure = m_fig.group(1)
        elif line.startswith("```"):
            end = i + 1
            while end < len(lines) and not lines[end].startswith("```"):
                end += 1
            if line.strip() == "```bash":
                blocks.append({"line": i + 1, "text": lines[i + 1:end], "options": options})
            elif line.strip() == "```text" and output:
                shown.append({"command": output, "first": i + 1, "end": end, "after": len(blocks)})
            options, output = {}, None
            i = end + 1
            continue
        elif figure and IMAGE.search(line):
            figures.append({"file": figure, "image": IMAGE.search(line).group(1),
                            "after": len(blocks)})
            figure = None
        elif line.strip() and not line.startswith("<!--"):
            options, output = {}, None
        i += 1
    return blocks, shown, figures


def script_of(block, captures):
    """The block's commands with the remake options, and the captured commands' standard
    output written to their files too."""
    out, command = [], ""
    for line in block["text"]:
        if line.endswith("\\"):
            command += line[:-1] + " "
            continue
        command += line
        capture = next((c for c in captures if not c["found"] and squeezed(command) == c["command"]),
                       None)
        m = BKQUAKE.search(command)
        if m and m.group(1) in block["options"]:
            at = len(command)
            for stop in (" #", " >", " |", " &&", " 2>"):
                k = command.find(stop, m.end())
                if k >= 0:
                    at = min(at, k)
            command = command[:at] + " " + block["options"][m.group(1)] + command[at:]
        if capture:
            capture["found"] = True
            command = "{ " + command + " ; } | tee '" + capture["file"] + "'"
        out.append(command)
        command = ""
    return "set -eo pipefail\n" + "\n".join(out) + "\n"


def remade_text(shown_lines, output):
    """The shown lines with each replaced by the program's line of the same words; the lines
    not found."""
    actual = output.splitlines()
    new, missing, nxt = [], [], 0
    for line in shown_lines:
        if not line.strip():
            new.append(line)
            continue
        k = nxt
        while k < len(actual) and words(actual[k]) != words(line):
            k += 1
        if k == len(actual):
            missing.append(line)
            new.append(line)
        else:
            new.append(actual[k])
            nxt = k + 1
    return new, missing


def scratch_folder(scratch, name, binary):
    """A folder under `scratch` holding data/, analysis/ and build/bkquake, as the pages'
    commands expect."""
    work = os.path.join(scratch, name)
    os.makedirs(os.path.join(work, "build"))
    os.symlink(os.path.join(ROOT, "data"), os.path.join(work, "data"))
    os.symlink(os.path.join(ROOT, "analysis"), os.path.join(work, "analysis"))
    os.symlink(os.path.abspath(binary), os.path.join(work, "build", "bkquake"))
    return work


def remake_long(study, k, binary, scratch, check):
    """Runs one LONG study and copies its figures over the images."""
    name = ", ".join(study["pages"])
    if check:
        for image in study["figures"].values():
            print(f"{name}: --long would remake {image}")
        return True
    work = scratch_folder(scratch, f"long{k}", binary)
    print(f"{name}: the long study ({len(study['commands'])} commands) ...", flush=True)
    script = os.path.join(work, "long.sh")
    with open(script, "w") as f:
        f.write("set -eo pipefail\n" + "\n".join(study["commands"]) + "\n")
    env = dict(os.environ, MPLBACKEND="Agg")
    if subprocess.run(["bash", script], cwd=work, env=env, stdout=subprocess.DEVNULL).returncode:
        print(f"{name}: the long study failed ({script})", file=sys.stderr)
        return False
    ok = True
    for made, image in study["figures"].items():
        if not os.path.isfile(os.path.join(work, made)):
            print(f"{name}: no {made} for {image}", file=sys.stderr)
            ok = False
            continue
        shutil.copyfile(os.path.join(work, made), os.path.join(ROOT, image))
        print(f"{name}: {image} remade")
    return ok


def remake(page, binary, scratch, check):
    lines = open(page, encoding="utf-8").read().split("\n")
    blocks, shown, figures = parse(lines)
    if not shown and not figures:
        return True
    rel = os.path.relpath(page, ROOT)
    work = scratch_folder(scratch, os.path.splitext(os.path.basename(page))[0], binary)
    captures = [{"command": squeezed(s["command"]), "file": os.path.join(work, f"shown{k}.txt"),
                 "found": False} for k, s in enumerate(shown)]
    last = max([s["after"] for s in shown] + [f["after"] for f in figures])
    for i, block in enumerate(blocks[:last]):
        mine = [c for k, c in enumerate(captures) if shown[k]["after"] > i]
        script = os.path.join(work, f"block{i}.sh")
        with open(script, "w") as f:
            f.write(script_of(block, mine))
        print(f"{rel}: the block at line {block['line']} ...", flush=True)
        env = dict(os.environ, MPLBACKEND="Agg")
        if subprocess.run(["bash", script], cwd=work, env=env,
                          stdout=subprocess.DEVNULL).returncode != 0:
            print(f"{rel}: the block at line {block['line']} failed ({script})", file=sys.stderr)
            return False
    ok = True
    # Bottom up, so that the line numbers above stay valid.
    for k in reversed(range(len(shown))):
        s = shown[k]
        if not captures[k]["found"]:
            print(f"{rel}: `{s['command']}` (printout at line {s['first']}) is run by no block "
                  "above it", file=sys.stderr)
            ok = False
            continue
        output = open(captures[k]["file"], encoding="utf-8").read()
        new, missing = remade_text(lines[s["first"]:s["end"]], output)
        for m in missing:
            print(f"{rel}: the program no longer prints a line like \"{m}\" "
                  f"(printout at line {s['first']}); edit it by hand:\n{output}", file=sys.stderr)
            ok = False
        if new != lines[s["first"]:s["end"]]:
            print(f"{rel}: the printout at line {s['first']} " +
                  ("would change" if check else "remade"))
            lines[s["first"]:s["end"]] = new
    for fig in figures:
        made = os.path.join(work, fig["file"])
        image = os.path.normpath(os.path.join(os.path.dirname(page), fig["image"]))
        if not os.path.isfile(made):
            print(f"{rel}: no {fig['file']} for {fig['image']}", file=sys.stderr)
            ok = False
        elif not check:
            shutil.copyfile(made, image)
            print(f"{rel}: {os.path.relpath(image, ROOT)} remade")
    if not check:
        with open(page, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pages", nargs="*", help="markdown pages (default: tutorials and how-to)")
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bkquake"))
    ap.add_argument("--keep", help="scratch folder to keep (must not exist)")
    ap.add_argument("--check", action="store_true", help="write nothing; say what would change")
    ap.add_argument("--long", action="store_true",
                    help="also remake the figures of the 10^6-event studies (CPU-minutes)")
    a = ap.parse_args()
    pages = a.pages or sorted(glob.glob(os.path.join(ROOT, "docs", "tutorials", "*.md")) +
                              glob.glob(os.path.join(ROOT, "docs", "how-to", "*.md")))
    chosen = {os.path.abspath(p) for p in pages}
    long = [s for s in LONG if a.long and (not a.pages or any(
        os.path.join(ROOT, p) in chosen for p in s["pages"]))]
    if not os.access(a.binary, os.X_OK):
        sys.exit(f"remake_doc_examples.py: no bkquake binary at {a.binary} (build it, or --binary)")
    scratch = a.keep or tempfile.mkdtemp(prefix="bkq_doc_examples_")
    if a.keep:
        os.makedirs(scratch)
    try:
        ok = all([remake(os.path.abspath(p), a.binary, scratch, a.check) for p in pages] +
                 [remake_long(s, k, a.binary, scratch, a.check) for k, s in enumerate(long)])
    finally:
        if not a.keep:
            shutil.rmtree(scratch, ignore_errors=True)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
