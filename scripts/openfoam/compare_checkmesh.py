#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compare checkMeshQuality's report with OpenFOAM v1912 checkMesh's (for checkmesh_sweep.sh).

Usage:
  compare_checkmesh.py diff CHECKMESH_LOG OURS_LOG   print the comparison of two reports
  compare_checkmesh.py mesh MESH_DIR                 MESH_DIR/checkMesh.<mode>.log against
                                                     checkMeshQuality.<mode>.log (modes plain,
                                                     all) -> MESH_DIR/result.json
  compare_checkmesh.py case WORK_DIR                 one status line for a swept case
  compare_checkmesh.py summary OUT_DIR               OUT_DIR/summary.{md,csv,json}; prints the
                                                     Markdown
  compare_checkmesh.py recompare OUT_DIR             every result.json again from the logs
                                                     (after a change of the rule), then summary

Comparison rule:
- Compared: the lines from the first "Time = " line on (before it: start-up, kept in the
  JSON as preamble), without those that differ by nature. Dropped: the banner, the header lines
  (Build/Arch/Exec/Date/Time/Host/PID/I/O/Case/nProcs/trapFpe/fileModificationChecking/
  allowSystemOperations; ours: the "meshMorph ... : checkMeshQuality" and Threads lines),
  "Create time", "Create mesh/polyMesh for time = T", checkMesh's echo of its options
  ("Enabling all ... checks.", "Disabling all topology checks."), ours "Read mesh (...) in",
  "Checked mesh in", "Wrote N sets to ... in", timings (ExecutionTime), the closing "End",
  the "in file X at line N." lines of FOAM warnings, blank lines and trailing blanks.
- The remaining lines are aligned (difflib on their text with every number replaced by #).
  A line agrees in text when that skeleton is the same, blanks included ("spacing" when only
  the blanks differ).
- Every number of checkMesh's report is compared with the number at the same place of the
  aligned line of ours: it agrees when |a - b| <= 1e-6 max(|a|, |b|) (equal when both are 0).
  A number in a line that ours lacks does not agree. Disagreeing numbers are classed as
  "print" (at most one unit of the 6th significant digit apart, or of the last digit
  printed when more are: rounding at checkMesh's printed precision), "noise" (both below 1e-12 in magnitude: cancellation noise) or "value".
- The verdict is the last "Mesh OK." / "Failed N mesh checks." line.
Standard library only.
"""

import csv
import difflib
import json
import math
import re
import sys
from collections import Counter, OrderedDict, defaultdict
from pathlib import Path

REL_TOL = 1e-6
NOISE = 1e-12
MODES = ("plain", "all")
MAX_DIFFS = 20  # differing lines kept per comparison

NUMBER = re.compile(r"(?<![\w.+-])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?!\w|\.\d)")
VERDICT = re.compile(r"^(Mesh OK\.|Failed \d+ mesh checks\.)$")
HEADER_KEYS = ("Build", "Arch", "Exec", "Date", "Time", "Host", "PID", "I/O", "Case",
               "nProcs", "trapFpe", "fileModificationChecking", "allowSystemOperations",
               "Threads")
HEADER = re.compile(r"^(%s)\s*:" % "|".join(re.escape(k) for k in HEADER_KEYS))
DROPPED = [
    re.compile(r"^meshMorph .* : checkMeshQuality"),
    re.compile(r"^// \* \* \*"),
    re.compile(r"^Create time$"),
    re.compile(r"^Create (poly)?[mM]esh( \S+)? for time = "),
    re.compile(r"^Enabling all .* checks\.$"),
    re.compile(r"^Disabling all topology checks\.$"),
    re.compile(r"^Read mesh \(.*\) in "),
    re.compile(r"^Checked mesh in "),
    re.compile(r"^Wrote \d+ sets? to .* in "),
    re.compile(r"^ExecutionTime = "),
    re.compile(r"^End$"),
    re.compile(r"^\s+in file .* at line \d+\.?$"),
]


# ---------------------------------------------------------------------------------------
# one pair of reports

def normalized_lines(text):
    """The lines that are compared, as (line number in the log, text): from the first
    "Time = " line on (the preamble before it is start-up: banner, header, Create time/mesh,
    checkMesh's time-selection warnings, its echo of the options, our "Read mesh" line)."""
    lines = all_lines(text)
    for k, (_, line) in enumerate(lines):
        if line.startswith("Time = "):
            return lines[k:]
    return lines


def preamble_lines(text):
    """The lines before the first "Time = " (not compared; kept in the JSON)."""
    lines = all_lines(text)
    for k, (_, line) in enumerate(lines):
        if line.startswith("Time = "):
            return [l for _, l in lines[:k]]
    return []


def all_lines(text):
    lines = text.splitlines()
    out = []
    in_banner = False
    for number, line in enumerate(lines, 1):
        stripped = line.rstrip()
        if stripped.startswith("/*---") and not out:
            in_banner = True
            continue
        if in_banner:
            if stripped.startswith("\\*---"):
                in_banner = False
            continue
        if not stripped:
            continue
        if HEADER.match(stripped) and not stripped.startswith("Time = "):
            continue
        if any(p.match(stripped) for p in DROPPED):
            continue
        out.append((number, stripped))
    return out


def skeleton(line):
    return NUMBER.sub("#", line)


def numbers(line):
    return [m.group(0) for m in NUMBER.finditer(line)]


def verdicts(text):
    return [line.strip() for line in text.splitlines() if VERDICT.match(line.strip())]


def significant_digits(token):
    mantissa = token.lower().partition("e")[0].lstrip("+-").replace(".", "").lstrip("0")
    return len(mantissa)


def print_unit(a_tok, b_tok, scale):
    """One unit of the last digit checkMesh prints for a value of magnitude scale: it prints
    6 significant digits (more when the case's writePrecision is higher; the longer token
    tells), trailing zeros dropped."""
    digits = max(6, significant_digits(a_tok), significant_digits(b_tok))
    return 10.0 ** (math.floor(math.log10(scale)) - digits + 1)


def compare_numbers(a_tok, b_tok):
    """None when they agree, else the class of the difference."""
    a, b = float(a_tok), float(b_tok)
    scale = max(abs(a), abs(b))
    if a == b or abs(a - b) <= REL_TOL * scale:
        return None
    if scale < NOISE:
        return "noise"
    if abs(a - b) <= 1.000001 * print_unit(a_tok, b_tok, scale):
        return "print"
    return "value"


def compare_texts(of_text, mm_text):
    """The comparison of checkMesh's report (of) with ours (mm), as a dict."""
    of_lines = normalized_lines(of_text)
    mm_lines = normalized_lines(mm_text)
    of_skel = [skeleton(t) for _, t in of_lines]
    mm_skel = [skeleton(t) for _, t in mm_lines]
    diffs = []
    n_text_diffs = 0
    numbers_total = sum(len(numbers(t)) for _, t in of_lines)
    numbers_agree = 0
    number_classes = Counter()

    def pair(i, j):
        nonlocal n_text_diffs, numbers_agree
        of_t, mm_t = of_lines[i][1], mm_lines[j][1]
        kind = None
        if of_skel[i] != mm_skel[j]:
            kind = "spacing" if of_skel[i].split() == mm_skel[j].split() else "text"
            n_text_diffs += 1
        a, b = numbers(of_t), numbers(mm_t)
        bad = []
        if len(a) == len(b):
            for x, y in zip(a, b):
                c = compare_numbers(x, y)
                if c is None:
                    numbers_agree += 1
                else:
                    bad.append(c)
                    number_classes[c] += 1
        else:
            if a:
                number_classes["unpaired"] += len(a)
        if kind is None and bad:
            kind = "number"
        if kind:
            diffs.append({"kind": kind, "classes": sorted(set(bad)),
                          "checkMesh": of_t, "ours": mm_t,
                          "line": of_lines[i][0], "oursLine": mm_lines[j][0]})

    matcher = difflib.SequenceMatcher(None, of_skel, mm_skel, autojunk=False)
    for tag, i1, i2, j1, j2 in matcher.get_opcodes():
        if tag == "equal":
            for k in range(i2 - i1):
                pair(i1 + k, j1 + k)
            continue
        n = min(i2 - i1, j2 - j1) if tag == "replace" else 0
        for k in range(n):
            pair(i1 + k, j1 + k)
        for i in range(i1 + n, i2):
            n_text_diffs += 1
            if numbers(of_lines[i][1]):
                number_classes["unpaired"] += len(numbers(of_lines[i][1]))
            diffs.append({"kind": "missing", "classes": [], "checkMesh": of_lines[i][1],
                          "ours": None, "line": of_lines[i][0], "oursLine": None})
        for j in range(j1 + n, j2):
            n_text_diffs += 1
            diffs.append({"kind": "extra", "classes": [], "checkMesh": None,
                          "ours": mm_lines[j][1], "line": None, "oursLine": mm_lines[j][0]})
    diffs.sort(key=lambda d: (d["line"] if d["line"] is not None else
                              _nearest_line(d, of_lines, mm_lines, matcher)))
    of_verdicts, mm_verdicts = verdicts(of_text), verdicts(mm_text)
    of_verdict = of_verdicts[-1] if of_verdicts else None
    mm_verdict = mm_verdicts[-1] if mm_verdicts else None
    return OrderedDict([
        ("linesCheckMesh", len(of_lines)),
        ("linesOurs", len(mm_lines)),
        ("verdictCheckMesh", of_verdict),
        ("verdictOurs", mm_verdict),
        ("verdictAgree", of_verdict is not None and of_verdicts == mm_verdicts),
        ("textAgree", n_text_diffs == 0),
        ("textDiffs", n_text_diffs),
        ("numbersTotal", numbers_total),
        ("numbersAgree", numbers_agree),
        ("numberDiffClasses", dict(number_classes)),
        ("diffs", diffs[:MAX_DIFFS]),
        ("diffsTotal", len(diffs)),
        ("preambleCheckMesh", preamble_lines(of_text)),
        ("preambleOurs", preamble_lines(mm_text)),
    ])


def _nearest_line(diff, of_lines, mm_lines, matcher):
    """Sort key of an extra line of ours: the checkMesh line it would precede."""
    j = next(k for k, (n, _) in enumerate(mm_lines) if n == diff["oursLine"])
    for a, b, size in matcher.get_matching_blocks():
        if b > j:
            return (of_lines[a][0] - 0.5) if a < len(of_lines) else float("inf")
    return float("inf")


def read_text(path):
    try:
        return Path(path).read_text(errors="replace")
    except FileNotFoundError:
        return None


def read_rc(path):
    try:
        return int(Path(path).read_text().strip())
    except (FileNotFoundError, ValueError):
        return None


def error_excerpt(text):
    """The first FATAL ERROR lines (or the last lines) of a failed run."""
    if text is None:
        return None
    lines = [l.rstrip() for l in text.splitlines() if l.strip()]
    for k, line in enumerate(lines):
        if "FATAL" in line or "error:" in line.lower():
            return " | ".join(lines[k:k + 3])
    return " | ".join(lines[-3:])


def compare_mode(mesh_dir, mode):
    of_text = read_text(mesh_dir / f"checkMesh.{mode}.log")
    mm_text = read_text(mesh_dir / f"checkMeshQuality.{mode}.log")
    of_rc = read_rc(mesh_dir / f"checkMesh.{mode}.rc")
    mm_rc = read_rc(mesh_dir / f"checkMeshQuality.{mode}.rc")
    if of_text is None or mm_text is None:
        return None
    result = compare_texts(of_text, mm_text)
    result["rcCheckMesh"] = of_rc
    result["rcOurs"] = mm_rc
    # status: ok (checkMesh gave a verdict), checkMeshFailed (it did not), oursFailed (only
    # ours gave none), timeout
    if of_rc == 124 or mm_rc == 124:
        status = "timeout"
    elif result["verdictCheckMesh"] is None:
        status = "checkMeshFailed"
    elif result["verdictOurs"] is None:
        status = "oursFailed"
    else:
        status = "ok"
    result["status"] = status
    if result["verdictCheckMesh"] is None:
        result["errorCheckMesh"] = error_excerpt(of_text)
    if result["verdictOurs"] is None:
        result["errorOurs"] = error_excerpt(mm_text)
    return result


PLAIN_PATCH_TYPES = {"patch", "wall", "empty", "symmetry", "symmetryPlane"}


def patch_types(case_dir, region):
    """The patch types of a mesh's boundary file (the latest time's when a time directory
    has one), or [] when it cannot be read."""
    sub = Path(region) / "polyMesh" if region else Path("polyMesh")
    candidates = [case_dir / "constant" / sub]
    times = []
    for t in case_dir.iterdir() if case_dir.is_dir() else []:
        try:
            times.append((float(t.name), t))
        except ValueError:
            pass
    candidates = [t / sub for _, t in sorted(times, key=lambda x: x[0], reverse=True)] + candidates
    for d in candidates:
        for name in ("boundary", "boundary.gz"):
            f = d / name
            if f.is_file():
                try:
                    if name.endswith(".gz"):
                        import gzip
                        text = gzip.open(f, "rt", errors="replace").read()
                    else:
                        text = f.read_text(errors="replace")
                except OSError:
                    return []
                return sorted(set(re.findall(r"^\s*type\s+(\w+)\s*;", text, re.M)))
    return []


def compare_mesh(mesh_dir):
    mesh_dir = Path(mesh_dir)
    case_rel, _, region = (mesh_dir / "mesh.tsv").read_text().rstrip("\n").partition("\t")
    result = OrderedDict([("mesh", case_rel), ("region", region), ("modes", OrderedDict())])
    copy = mesh_dir.parent.parent / "case"
    old = mesh_dir / "result.json"
    if copy.is_dir():
        result["patchTypes"] = patch_types(copy / case_rel, region)
    elif old.exists():  # the copy was removed: keep what was read when it was there
        result["patchTypes"] = json.loads(old.read_text()).get("patchTypes", [])
    for mode in MODES:
        r = compare_mode(mesh_dir, mode)
        if r is not None:
            result["modes"][mode] = r
    (mesh_dir / "result.json").write_text(json.dumps(result, indent=1) + "\n")
    return result


def agrees(r):
    return (r["status"] == "ok" and r["verdictAgree"] and r["textAgree"]
            and r["numbersAgree"] == r["numbersTotal"])


# ---------------------------------------------------------------------------------------
# a swept case and the summary

def load_case(work):
    work = Path(work).resolve()
    case_id, rel, method, detail = (work / "case.tsv").read_text().rstrip("\n").split("\t")
    mesh_error = read_text(work / "mesh_error")
    meshes = []
    for rj in sorted((work / "meshes").glob("*/result.json")):
        meshes.append(json.loads(rj.read_text()))
    case = OrderedDict([("id", case_id), ("tutorial", rel), ("method", method),
                        ("copy", str(work / "case")),
                        ("detail", detail), ("meshError", mesh_error.strip() if mesh_error else None),
                        ("meshes", meshes)])
    if mesh_error:
        case["meshLog"] = mesh_log_excerpt(work)
    return case


def mesh_log_excerpt(work):
    """The reason a mesh step failed: the failed step of steps.log, or a log's error (the
    path of the case copy shortened to <case>)."""
    text = _mesh_log_excerpt(work)
    return text.replace(str(work / "case"), "<case>") if text else text


def _mesh_log_excerpt(work):
    steps = read_text(work / "steps.log")
    if steps:
        failed = [l for l in steps.splitlines() if l.startswith("FAILED")]
        if failed:
            return failed[0]
    logs = sorted(work.glob("log.*"), key=lambda p: p.stat().st_mtime, reverse=True)
    logs += sorted(work.glob("case/**/log.*"), key=lambda p: p.stat().st_mtime, reverse=True)
    for log in logs:
        text = read_text(log)
        if text and "administrator rights" in text:
            return (f"{log.name}: dynamic code (#codeStream/#calc) refused: the sweep runs as "
                    "root, and Debian's openfoam has no wmake to compile it anyway")
        excerpt = error_excerpt(text)
        if excerpt:
            return f"{log.name}: {excerpt}"
    return None


def case_line(case):
    meshes = case["meshes"]
    parts = []
    if case["meshError"]:
        parts.append(case["meshError"] + (f" ({case['meshLog']})" if case.get("meshLog") else ""))
    if meshes:
        comps = [m["modes"][mode] for m in meshes for mode in m["modes"]]
        n = len(comps)
        parts.append(
            f"{len(meshes)} mesh{'es' if len(meshes) != 1 else ''}: "
            f"verdicts {sum(c['verdictAgree'] for c in comps)}/{n}, "
            f"text {sum(c['textAgree'] and c['status'] == 'ok' for c in comps)}/{n}, "
            f"numbers {sum(c['numbersAgree'] for c in comps)}/{sum(c['numbersTotal'] for c in comps)}")
        statuses = Counter(c["status"] for c in comps if c["status"] != "ok")
        if statuses:
            parts.append(", ".join(f"{k} {v}" for k, v in sorted(statuses.items())))
        parts.append("all agree" if all(agrees(c) for c in comps) else "MISMATCH")
    return "; ".join(parts) if parts else "no mesh"


def diff_text(d):
    if d["kind"] == "failed":
        return f"ours failed: `{d['ours'].strip()}`"
    if d["kind"] == "missing":
        return f"checkMesh: `{d['checkMesh'].strip()}` / ours: (missing)"
    if d["kind"] == "extra":
        return f"checkMesh: (none) / ours: `{d['ours'].strip()}`"
    return f"checkMesh: `{d['checkMesh'].strip()}` / ours: `{d['ours'].strip()}`"


def diff_signature(d):
    """The group of a differing line: its text with the numbers as #."""
    if d["kind"] == "missing":
        return "missing in ours: " + skeleton(d["checkMesh"]).strip()
    if d["kind"] == "extra":
        return "extra in ours: " + skeleton(d["ours"]).strip()
    if d["kind"] == "number":
        return "numbers (" + "/".join(d["classes"]) + "): " + skeleton(d["checkMesh"]).strip()
    return "text: " + skeleton(d["checkMesh"]).strip() + "  ->  " + skeleton(d["ours"]).strip()


def md_escape(text):
    return text.replace("|", "\\|")


def summary(out_dir):
    out_dir = Path(out_dir)
    cases = [load_case(w) for w in sorted((out_dir / "cases").iterdir())
             if (w / "case.tsv").exists()]
    skipped = []
    skipped_file = out_dir / "skipped.tsv"
    if skipped_file.exists():
        for line in skipped_file.read_text().splitlines():
            if line.strip():
                rel, _, reason = line.partition("\t")
                skipped.append({"tutorial": rel, "reason": reason})
    sweep = {}
    if (out_dir / "sweep.tsv").exists():
        for line in (out_dir / "sweep.tsv").read_text().splitlines():
            k, _, v = line.partition("\t")
            sweep[k] = v

    rows = []
    per_mode = {m: Counter() for m in MODES}
    number_classes = Counter()
    groups = defaultdict(list)  # signature -> [(case, mesh, mode, diff)]
    mismatches = []
    failures = []
    for case in cases:
        for mesh in case["meshes"]:
            name = mesh["mesh"] + (f" -region {mesh['region']}" if mesh["region"] else "")
            for mode, r in mesh["modes"].items():
                c = per_mode[mode]
                c["comparisons"] += 1
                c["status " + r["status"]] += 1
                if r["status"] == "ok":
                    c["verdicts agree"] += r["verdictAgree"]
                    c["text agrees"] += r["textAgree"]
                    c["numbers"] += r["numbersTotal"]
                    c["numbers agree"] += r["numbersAgree"]
                    c["all agree"] += agrees(r)
                    for k, v in r["numberDiffClasses"].items():
                        number_classes[k] += v
                first = r["diffs"][0] if r["diffs"] else None
                rows.append(OrderedDict([
                    ("id", case["id"]), ("tutorial", case["tutorial"]), ("method", case["method"]),
                    ("mesh", mesh["mesh"]), ("region", mesh["region"]), ("mode", mode),
                    ("status", r["status"]), ("rcCheckMesh", r["rcCheckMesh"]), ("rcOurs", r["rcOurs"]),
                    ("verdictCheckMesh", r["verdictCheckMesh"]), ("verdictOurs", r["verdictOurs"]),
                    ("verdictAgree", r["verdictAgree"]), ("textAgree", r["textAgree"]),
                    ("textDiffs", r["textDiffs"]), ("numbersTotal", r["numbersTotal"]),
                    ("numbersAgree", r["numbersAgree"]),
                    ("firstDiffCheckMesh", first["checkMesh"].strip() if first and first["checkMesh"] else ""),
                    ("firstDiffOurs", first["ours"].strip() if first and first["ours"] else ""),
                ]))
                if r["status"] == "checkMeshFailed":
                    failures.append((case, name, mode, "checkMesh: " + (r.get("errorCheckMesh") or "?")
                                     + ("; ours: " + (r.get("verdictOurs") or r.get("errorOurs") or "?"))))
                    continue
                if r["status"] in ("oursFailed", "timeout"):
                    error = r.get("errorOurs") or f"exit {r['rcOurs']}"
                    failures.append((case, name, mode, r["status"] + ": " + error))
                    mismatches.append((case, name, mode, r))
                    # one group for the failure, not one per line it did not print
                    sig = r["status"] + ": " + skeleton(error.replace(case["copy"], "<case>"))
                    groups[sig].append((case, name, mode, {"kind": "failed", "checkMesh": None,
                                                           "ours": error.replace(case["copy"], "<case>"),
                                                           "patchTypes": mesh.get("patchTypes", [])}))
                    continue
                if not agrees(r):
                    mismatches.append((case, name, mode, r))
                    seen = set()
                    for d in r["diffs"]:
                        sig = diff_signature(d)
                        if sig not in seen:
                            seen.add(sig)
                            groups[sig].append((case, name, mode,
                                                dict(d, patchTypes=mesh.get("patchTypes", []))))

    n_meshes = sum(len(c["meshes"]) for c in cases)
    mesh_failed = [c for c in cases if c["meshError"]]
    methods = Counter(c["method"] for c in cases)
    totals = Counter()
    for m in MODES:
        totals.update(per_mode[m])

    md = []
    md.append("# checkMeshQuality against OpenFOAM v1912 checkMesh: tutorial sweep\n")
    if sweep:
        md.append(f"Tutorials: `{sweep.get('tutorials', '?')}`; checker: `{sweep.get('checker', '?')}`; "
                  f"options: `{sweep.get('options', '').strip() or '(none)'}`; "
                  f"{sweep.get('started', '?')} .. {sweep.get('finished', '(unfinished)')}\n")
    md.append("## Numbers\n")
    md.append(f"- Tutorial cases run: {len(cases)} ("
              + ", ".join(f"{k} {v}" for k, v in sorted(methods.items())) + f"); "
              f"mesh step failed or made no mesh: {len(mesh_failed)}; tutorials skipped: {len(skipped)}")
    md.append(f"- Meshes checked: {n_meshes}; comparisons (mesh x mode): {totals['comparisons']}")
    md.append("")
    md.append("| mode | comparisons | checkMesh failed | ours failed | timeout | verdicts agree | text agrees | numbers agree | all agree |")
    md.append("|---|---|---|---|---|---|---|---|---|")
    for m in MODES + ("total",):
        c = totals if m == "total" else per_mode[m]
        ok = c["status ok"]
        label = {"plain": "plain", "all": "-allGeometry -allTopology", "total": "**total**"}[m]
        md.append(f"| {label} | {c['comparisons']} | {c['status checkMeshFailed']} | "
                  f"{c['status oursFailed']} | {c['status timeout']} | {c['verdicts agree']}/{ok} | "
                  f"{c['text agrees']}/{ok} | {c['numbers agree']}/{c['numbers']} | {c['all agree']}/{ok} |")
    md.append("")
    md.append("Verdicts, text and numbers are counted over the comparisons where checkMesh gave a "
              "verdict. Numbers agree within 1e-6 relative; the disagreeing ones: "
              + (", ".join(f"{k} {v}" for k, v in sorted(number_classes.items())) or "none")
              + " (print: at most one unit of the last digit printed, the 6th significant one: "
                "rounding; noise: both below 1e-12: cancellation noise; unpaired: in a line ours "
                "lacks or words differently).\n")

    md.append("## Mismatches grouped by differing line\n")
    if not groups:
        md.append("None.\n")
    else:
        md.append("Patch types: how many of the group's comparisons are on a mesh with a patch "
                  "of that type (patch, wall, empty and symmetry types not counted); a hint of the cause.\n")
        md.append("| comparisons | differing line (numbers as #) | patch types | example |")
        md.append("|---|---|---|---|")
        for sig, items in sorted(groups.items(), key=lambda kv: (-len(kv[1]), kv[0])):
            case, name, mode, d = items[0]
            ex = f"{case['tutorial']} [{case['method']}] {name} ({mode}): {diff_text(d)}"
            types = Counter(t for _, _, _, dd in items for t in set(dd.get("patchTypes", []))
                            if t not in PLAIN_PATCH_TYPES)
            types_text = ", ".join(f"{t} {n}" for t, n in types.most_common(4)) or "-"
            md.append(f"| {len(items)} | {md_escape(sig)} | {types_text} | {md_escape(ex)} |")
        md.append("")

    md.append("## Mismatching meshes (first differing lines)\n")
    if not mismatches:
        md.append("None.\n")
    for case, name, mode, r in mismatches:
        md.append(f"- **{case['tutorial']}** [{case['method']}] `{name}` ({mode}): "
                  f"verdict {r['verdictCheckMesh']} / ours {r['verdictOurs']}; "
                  f"{r['textDiffs']} differing lines, numbers {r['numbersAgree']}/{r['numbersTotal']}")
        if r["status"] != "ok":
            md.append(f"  - {r['status']}: "
                      + md_escape((r.get("errorOurs") or "").replace(case["copy"], "<case>")))
            continue
        for d in r["diffs"][:3]:
            md.append(f"  - {md_escape(diff_text(d))}")
    md.append("")

    md.append("## Failures (a tool gave no verdict, or the mesh step failed)\n")
    if not failures and not mesh_failed:
        md.append("None.\n")
    for case, name, mode, text in failures:
        text = text.replace(case["copy"], "<case>")
        md.append(f"- {case['tutorial']} [{case['method']}] `{name}` ({mode}): {md_escape(text)}")
    for case in mesh_failed:
        md.append(f"- mesh step: {case['tutorial']} [{case['method']}]: {case['meshError']}"
                  + (f" ({md_escape(case['meshLog'])})" if case.get("meshLog") else "")
                  + (f"; {len(case['meshes'])} mesh(es) found and checked anyway" if case["meshes"] else ""))
    md.append("")

    md.append("## Skipped tutorials\n")
    by_reason = defaultdict(list)
    for s in skipped:
        by_reason[s["reason"]].append(s["tutorial"])
    if not skipped:
        md.append("None.\n")
    for reason, tuts in sorted(by_reason.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        md.append(f"- {reason}: {len(tuts)}: " + ", ".join(tuts))
    md.append("")
    text = "\n".join(md)
    (out_dir / "summary.md").write_text(text)

    with open(out_dir / "summary.csv", "w", newline="") as f:
        if rows:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    data = OrderedDict([
        ("sweep", sweep),
        ("totals", {m: dict(per_mode[m]) for m in MODES}),
        ("numberDiffClasses", dict(number_classes)),
        ("meshes", n_meshes),
        ("groups", [{"signature": sig, "comparisons": len(items),
                     "cases": sorted({f"{c['tutorial']} [{c['method']}] {n} ({m})" for c, n, m, _ in items})}
                    for sig, items in sorted(groups.items(), key=lambda kv: -len(kv[1]))]),
        ("cases", cases),
        ("skipped", skipped),
    ])
    (out_dir / "summary.json").write_text(json.dumps(data, indent=1) + "\n")
    print(text)


def main(argv):
    if len(argv) >= 2 and argv[1] in ("-h", "-help", "--help"):
        print(__doc__)
        return 0
    if len(argv) == 4 and argv[1] == "diff":
        r = compare_texts(Path(argv[2]).read_text(errors="replace"),
                          Path(argv[3]).read_text(errors="replace"))
        print(json.dumps(r, indent=1))
        return 0
    if len(argv) == 3 and argv[1] == "mesh":
        compare_mesh(argv[2])
        return 0
    if len(argv) == 3 and argv[1] == "case":
        print(case_line(load_case(argv[2])))
        return 0
    if len(argv) == 3 and argv[1] == "summary":
        summary(argv[2])
        return 0
    if len(argv) == 3 and argv[1] == "recompare":
        for tsv in sorted(Path(argv[2]).glob("cases/*/meshes/*/mesh.tsv")):
            compare_mesh(tsv.parent)
        summary(argv[2])
        return 0
    sys.stderr.write(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
