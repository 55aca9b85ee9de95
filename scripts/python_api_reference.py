#!/usr/bin/env python3
"""Writes the Python API reference (docs/python_api.md) from the docstrings of the built module.

    PYTHONPATH=<build>/python python3 scripts/python_api_reference.py [--out docs/python_api.md] [--check]

Every public function, class, method, property and enum value of `stickslip` is listed with its
signatures (pybind11's) and its docstring. --out names the index page; the entries go to pages of
at most about PAGE_LINES lines in the folder of the same name without .md (docs/python_api/),
functions and classes in alphabetical order, the index listing every name with its page. With
--check the script exits with status 1, naming them, when a public name has no docstring (the
walk of tests/python/test_api.py)."""
import argparse
import glob
import inspect
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))

import stickslip as ss  # noqa: E402
from test_api import SIGNATURE, enum_member_docs, is_enum, missing_docstrings, own_text  # noqa: E402


PAGE_LINES = 380
ADDRESS = re.compile(r" at 0x[0-9a-fA-F]+>")


def signatures(doc):
    """pybind11's signature lines of a docstring ("name(arg: type = default) -> type")."""
    out = []
    for line in (doc or "").splitlines():
        line = line.strip()
        if SIGNATURE.match(line) and "(*args, **kwargs)" not in line:
            line = line.split(". ", 1)[1] if line[:1].isdigit() else line
            out.append(ADDRESS.sub(">", line))  # default objects' addresses change every run
    return out


def text(doc):
    """The docstring's own text, overloads joined."""
    return "\n\n".join(t for t in own_text(doc) if t)


def callable_entry(name, obj, level):
    lines = ["#" * level + " `" + name + "`", ""]
    sigs = signatures(obj.__doc__)
    if sigs:
        lines += ["```", *sigs, "```", ""]
    body = text(obj.__doc__)
    if body:
        lines += [body, ""]
    return lines


def class_entry(name, cls, level):
    lines = ["#" * level + " class `" + name + "`", ""]
    if is_enum(cls):
        head, members = enum_member_docs(cls)
        lines += [head, "", "| value | meaning |", "| --- | --- |"]
        lines += ["| `%s` | %s |" % (m, members.get(m, "")) for m in cls.__members__]
        return lines + [""]
    lines += [(cls.__doc__ or "").strip(), ""]
    properties, methods, nested = [], [], []
    for member, value in sorted(vars(cls).items()):
        if member.startswith("_") and member not in ("__init__", "__call__", "__len__"):
            continue
        if inspect.isclass(value):
            nested.append((member, value))
        elif isinstance(value, property):
            properties.append((member, value))
        elif member == "__init__" and "Initialize self" in (value.__doc__ or ""):
            continue  # no constructor of its own (a result type)
        elif callable(getattr(cls, member)):
            methods.append((member, getattr(cls, member)))
    if properties:
        lines += ["| property | |", "| --- | --- |"]
        lines += ["| `%s` | %s |" % (p, text(v.__doc__).replace("|", "\\|").replace("\n", " ")) for p, v in properties]
        lines.append("")
    for member, fn in methods:
        lines += callable_entry(name + "." + member, fn, level + 1)
    for member, inner in nested:
        lines += class_entry(name + "." + member, inner, level + 1)
    return lines


def pages(entries, stem):
    """Packs (name, lines) entries into pages of at most about PAGE_LINES lines (an entry longer
    than that gets a page of its own): a list of (file name, [names], lines)."""
    out, names, lines = [], [], []
    for name, entry in entries:
        if lines and len(lines) + len(entry) > PAGE_LINES:
            out.append((names, lines))
            names, lines = [], []
        names.append(name)
        lines += entry
    if lines:
        out.append((names, lines))
    return [("%s_%d.md" % (stem, k + 1), n, l) for k, (n, l) in enumerate(out)]


def reference(folder):
    """The index page's text and the entry pages {file name: text} (file names relative to
    `folder`, the index's folder name)."""
    functions = [(n, getattr(ss, n)) for n in sorted(dir(ss))
                 if not n.startswith("_") and callable(getattr(ss, n)) and not inspect.isclass(getattr(ss, n))]
    classes = [(n, getattr(ss, n)) for n in sorted(dir(ss)) if not n.startswith("_") and inspect.isclass(getattr(ss, n))]
    head = "Generated from the docstrings of the `stickslip` module %s by `scripts/python_api_reference.py` " \
           "(do not edit: regenerate it)." % getattr(ss, "__version__", "")
    index = ["# Python API reference", "", head + " How to use the module: [python.md](python.md).", "",
             (ss.__doc__ or "").strip(), ""]
    files = {}
    for title, stem, entries in (
            ("Functions", "functions", [(n, callable_entry(n, fn, 2)) for n, fn in functions]),
            ("Classes and enumerations", "classes", [(n, class_entry(n, c, 2)) for n, c in classes])):
        index += ["## " + title, "", "| page | names |", "| --- | --- |"]
        for file, names, lines in pages(entries, stem):
            page_title = "%s: %s to %s" % (title, names[0], names[-1])
            files[file] = "\n".join(["# Python API: " + page_title, "", head +
                                     " The index: [python_api.md](../python_api.md).", "", *lines]).rstrip() + "\n"
            index.append("| [%s](%s/%s) | %s |" % (page_title, folder, file, ", ".join("`%s`" % n for n in names)))
        index.append("")
    return "\n".join(index).rstrip() + "\n", files


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(HERE, "..", "docs", "python_api.md"))
    parser.add_argument("--check", action="store_true", help="exit 1 when a public name has no docstring")
    args = parser.parse_args()
    out = os.path.abspath(args.out)
    folder = os.path.splitext(os.path.basename(out))[0]
    pages_dir = os.path.join(os.path.dirname(out), folder)
    index, files = reference(folder)
    os.makedirs(pages_dir, exist_ok=True)
    for old in glob.glob(os.path.join(pages_dir, "*.md")):
        os.remove(old)  # pages of names that no longer exist
    with open(out, "w", encoding="utf-8") as f:
        f.write(index)
    for name, text_ in files.items():
        with open(os.path.join(pages_dir, name), "w", encoding="utf-8") as f:
            f.write(text_)
    missing = missing_docstrings(ss)
    if args.check and missing:
        print("without a docstring: " + ", ".join(missing), file=sys.stderr)
        return 1
    print("python_api_reference: wrote %s and %d pages in %s" % (out, len(files), pages_dir))
    return 0


if __name__ == "__main__":
    sys.exit(main())
