#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes docs/python-api.md, the Python module's reference, from the module itself.

    scripts/python-api-doc.py [--check] [OUTPUT]     (default OUTPUT: docs/python-api.md)

Every public class, function and attribute of `meshmorph` with its signature and
docstring, as pybind11 and the package's Python files give them: the page cannot say what
the code does not. --check compares instead of writing (exit 1 when the page is stale;
tests/python/test_api_doc.py runs it). Needs an importable meshmorph (PYTHONPATH=
build/<preset>/python, or the venv).
"""
import argparse
import difflib
import inspect
import re
import sys
from pathlib import Path

import meshmorph

SOURCE = Path(__file__).resolve().parents[1]
HEADER = """# The Python module `meshmorph`: reference

Generated from the module's docstrings by `scripts/python-api-doc.py` (do not edit; run it
after changing a binding). How to install the module and use it: [python.md](python.md).
"""


def public_names(obj):
    return [n for n in sorted(vars(obj)) if not n.startswith("_")]


def clean(doc):
    """A docstring as Markdown: pybind11's signature lines become code, the rest as is."""
    return inspect.cleandoc(doc or "").replace("meshmorph._core.", "meshmorph.")


def signature_and_text(doc):
    """pybind11 starts a function's docstring with its signature line(s)."""
    lines = clean(doc).splitlines()
    signatures, rest = [], []
    for line in lines:
        if not rest and "(" in line and ")" in line and " -> " in line:
            signatures.append(line)
        elif line.startswith("Overloaded function."):
            continue
        else:
            rest.append(line)
    return signatures, "\n".join(rest).strip()


def function_section(name, obj, level):
    signatures, text = signature_and_text(obj.__doc__)
    if not signatures:
        try:
            signatures = [f"{name}{inspect.signature(obj)}"]
        except (TypeError, ValueError):
            signatures = [name]
    out = [f"{'#' * level} `{name}`", "", "```python", *signatures, "```", ""]
    if text:
        out += [text, ""]
    return out


def constructor_section(name, cls):
    """The constructor as the caller writes it: Name(arguments), without self."""
    init = vars(cls)["__init__"]
    signatures, text = signature_and_text(init.__doc__)
    if signatures:
        signatures = [re.sub(r"^__init__\(self[^,)]*,? *", f"{name}(", line)
                      for line in signatures]
    else:
        signatures = [f"{name}{inspect.signature(cls)}"]
    out = [f"### `{name}(...)`", "", "```python", *signatures, "```", ""]
    return out + ([text, ""] if text else [])


def property_section(name, prop):
    text = clean(prop.__doc__)
    return [f"- `{name}`" + (f": {text}" if text else "")]


def class_section(name, cls):
    out = [f"## `meshmorph.{name}`", ""]
    text = clean(cls.__doc__)
    if text:
        out += [text, ""]
    methods, properties = [], []
    for member in public_names(cls):
        value = vars(cls)[member]
        if isinstance(value, property):
            properties += property_section(member, value)
        elif callable(value) or isinstance(value, (staticmethod, classmethod)):
            methods += function_section(member, getattr(cls, member), 3)
    if "__init__" in vars(cls):
        methods = constructor_section(name, cls) + methods
    if properties:
        out += ["Attributes:", ""] + properties + [""]
    return out + methods


def page():
    out = [HEADER]
    classes, functions, others = [], [], []
    for name in getattr(meshmorph, "__all__", public_names(meshmorph)):
        value = getattr(meshmorph, name)
        if inspect.isclass(value) and issubclass(value, BaseException):
            others.append(f"- `meshmorph.{name}` (exception, subclass of "
                          f"`{value.__mro__[1].__name__}`)"
                          + (f": {clean(value.__doc__).splitlines()[0]}"
                             if value.__doc__ else ""))
        elif inspect.isclass(value):
            classes.append((name, value))
        elif callable(value):
            functions.append((name, value))
        elif not inspect.ismodule(value):
            others.append(f"- `meshmorph.{name}` = `{value!r}`")
    for name, value in functions:
        out += function_section(f"meshmorph.{name}", value, 2)
    for name, value in classes:
        out += class_section(name, value)
    if others:
        out += ["## Constants and exceptions", ""] + others + [""]
    return "\n".join(out).rstrip("\n") + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true")
    parser.add_argument("output", nargs="?", type=Path, default=SOURCE / "docs/python-api.md")
    args = parser.parse_args()
    text = page()
    if args.check:
        old = args.output.read_text() if args.output.exists() else ""
        if old == text:
            print(f"{args.output}: up to date")
            return 0
        sys.stdout.writelines(difflib.unified_diff(old.splitlines(True), text.splitlines(True),
                                                   str(args.output), "generated"))
        print(f"{args.output} is stale: run scripts/python-api-doc.py", file=sys.stderr)
        return 1
    args.output.write_text(text)
    print(f"python-api-doc: wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
