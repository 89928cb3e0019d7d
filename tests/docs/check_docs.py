#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The documentation says what the tools do, and stays readable.

    check_docs.py SOURCE_DIR [--app NAME=EXECUTABLE ...]

Checks, each printed as it runs; exit status 1 when any fails:
- the README is a landing page: under 10,000 characters, no option table;
- README.md and docs/ quote no commit hashes and no internal issue numbers;
- every option an application's -help prints has a row in its reference page
  (docs/<NAME>.md), and that page lists no option -help does not know;
- every keyword the morphDict readers accept (their check_keywords lists in src/) is
  documented in docs/morphDict.md or docs/design-variables.md;
- every relative link of README.md, CHANGELOG.md, docs/*.md, tutorials/README.md and
  benchmarks/results/README.md names a file that exists, and its #anchor a heading there.
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

README_LIMIT = 10_000
HASH_OR_ISSUE = re.compile(r"\b[0-9a-f]{7,10}\b|issue [0-9]+")
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
OPTION_ROW = re.compile(r"^\| *`-")
# An option in the first column of a reference table row: `-name`, `-name ARG`.
ROW_OPTION = re.compile(r"`-([A-Za-z]+)")


def pages(src):
    """The Markdown files whose links are checked."""
    files = [src / "README.md", src / "CHANGELOG.md", src / "tutorials/README.md",
             src / "benchmarks/results/README.md"]
    return [f for f in files if f.exists()] + sorted((src / "docs").glob("*.md"))


def github_slug(heading):
    """The anchor GitHub gives a Markdown heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def prose_lines(path):
    """(line number, line) of a Markdown file, outside its ``` code blocks."""
    in_code = False
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if line.startswith("```"):
            in_code = not in_code
        elif not in_code:
            yield number, line


def anchors(path):
    """The anchors of a Markdown file's headings."""
    return {github_slug(line.lstrip("#")) for _, line in prose_lines(path) if line.startswith("#")}


def check_readme(src):
    text = (src / "README.md").read_text()
    errors = []
    if len(text) >= README_LIMIT:
        errors.append(f"README.md has {len(text)} characters (limit {README_LIMIT}): "
                      "move reference material into docs/")
    rows = [l for l in text.splitlines() if OPTION_ROW.match(l)]
    if rows:
        errors.append(f"README.md has option table rows (they belong in docs/): {rows[0]}")
    return errors


def check_no_hashes(src):
    errors = []
    for path in [src / "README.md"] + sorted((src / "docs").glob("*.md")):
        for number, line in enumerate(path.read_text().splitlines(), 1):
            m = HASH_OR_ISSUE.search(line)
            if m:
                errors.append(f"{path.relative_to(src)}:{number}: '{m.group(0)}' looks like a "
                              "commit hash or an internal issue number")
    return errors


def help_options(executable):
    """The options an application's -help prints (lines starting with '-name')."""
    out = subprocess.run([executable, "-help"], capture_output=True, text=True, timeout=60)
    if out.returncode != 0:
        raise RuntimeError(f"{executable} -help exited with {out.returncode}: {out.stderr}")
    options = set()
    for line in out.stdout.splitlines():
        m = re.match(r"^\s+-([A-Za-z]+)\b", line)
        if m:
            options.add(m.group(1))
    if not options:
        raise RuntimeError(f"{executable} -help printed no options:\n{out.stdout}")
    return options


def documented_options(page):
    """The options named in the first column of the page's table rows."""
    options = set()
    for line in page.read_text().splitlines():
        if OPTION_ROW.match(line):
            first_column = line.split("|")[1]
            options.update(ROW_OPTION.findall(first_column))
    return options


def check_app(src, name, executable):
    page = src / "docs" / f"{name}.md"
    if not page.exists():
        return [f"docs/{name}.md is missing (the reference of {name})"]
    in_help, in_page = help_options(executable), documented_options(page)
    errors = [f"docs/{name}.md: option -{o} of '{name} -help' has no row"
              for o in sorted(in_help - in_page)]
    errors += [f"docs/{name}.md: documents -{o}, which '{name} -help' does not know"
               for o in sorted(in_page - in_help)]
    return errors


def dictionary_keywords(src):
    """Every keyword in a check_keywords({...}) list of the morph and design readers."""
    keywords = set()
    for cpp in list((src / "src/meshmorph/morph").glob("*.cpp")) + \
            list((src / "src/meshmorph/design").glob("*.cpp")):
        for block in re.findall(r"check_keywords\(\s*\{([^}]*)\}", cpp.read_text()):
            keywords.update(re.findall(r'"(\w+)"', block))
    return keywords


def check_keywords(src):
    text = (src / "docs/morphDict.md").read_text() + \
        (src / "docs/design-variables.md").read_text()
    keywords = dictionary_keywords(src)
    if len(keywords) < 20:
        return [f"found only {len(keywords)} morphDict keywords in src/: the pattern is stale"]
    return [f"morphDict keyword '{k}' is not documented in docs/morphDict.md or "
            "docs/design-variables.md" for k in sorted(keywords) if f"`{k}" not in text]


def check_links(src):
    errors = []
    for page in pages(src):
        for number, line in prose_lines(page):
            for target in LINK.findall(line):
                if re.match(r"^[a-z]+:", target):
                    continue
                file_part, _, anchor = target.partition("#")
                path = (page.parent / file_part).resolve() if file_part else page
                where = f"{page.relative_to(src)}:{number}: link '{target}'"
                if not path.exists():
                    errors.append(f"{where}: no such file")
                elif anchor and path.suffix == ".md" and anchor not in anchors(path):
                    errors.append(f"{where}: no heading with anchor #{anchor}")
    return errors


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source_dir", type=Path)
    parser.add_argument("--app", action="append", default=[], metavar="NAME=EXECUTABLE")
    args = parser.parse_args()
    src = args.source_dir.resolve()

    checks = [("README is a landing page", lambda: check_readme(src)),
              ("no commit hashes or issue numbers", lambda: check_no_hashes(src)),
              ("morphDict keywords documented", lambda: check_keywords(src)),
              ("relative links resolve", lambda: check_links(src))]
    for app in args.app:
        name, _, executable = app.partition("=")
        checks.append((f"{name} -help and docs/{name}.md agree",
                       lambda n=name, e=executable: check_app(src, n, e)))
    failed = 0
    for title, check in checks:
        errors = check()
        print(f"{'ok  ' if not errors else 'FAIL'} {title}", flush=True)
        for e in errors:
            print(f"     {e}", flush=True)
        failed += bool(errors)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
