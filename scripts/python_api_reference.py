#!/usr/bin/env python3
"""Writes the Python API reference (docs/python_api.md) from the docstrings of the built module.

    PYTHONPATH=<build>/python python3 scripts/python_api_reference.py [--out docs/python_api.md] [--check]

Every public function, class, method, property and enum value of `stickslip` is listed with its
signatures (pybind11's) and its docstring. With --check the script exits with status 1, naming
them, when a public name has no docstring (the walk of tests/python/test_api.py)."""
import argparse
import inspect
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))

import stickslip as ss  # noqa: E402
from test_api import SIGNATURE, enum_member_docs, is_enum, missing_docstrings, own_text  # noqa: E402


def signatures(doc):
    """pybind11's signature lines of a docstring ("name(arg: type = default) -> type")."""
    out = []
    for line in (doc or "").splitlines():
        line = line.strip()
        if SIGNATURE.match(line) and "(*args, **kwargs)" not in line:
            out.append(line.split(". ", 1)[1] if line[:1].isdigit() else line)
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


def reference():
    functions = [(n, getattr(ss, n)) for n in sorted(dir(ss))
                 if not n.startswith("_") and callable(getattr(ss, n)) and not inspect.isclass(getattr(ss, n))]
    classes = [(n, getattr(ss, n)) for n in sorted(dir(ss)) if not n.startswith("_") and inspect.isclass(getattr(ss, n))]
    lines = ["# Python API reference", "",
             "Generated from the docstrings of the `stickslip` module %s by `scripts/python_api_reference.py`"
             % getattr(ss, "__version__", ""),
             "(do not edit: regenerate it). How to use the module: [python.md](python.md).", "",
             (ss.__doc__ or "").strip(), "", "## Functions", ""]
    for name, fn in functions:
        lines += callable_entry(name, fn, 3)
    lines += ["## Classes and enumerations", ""]
    for name, cls in classes:
        lines += class_entry(name, cls, 3)
    return "\n".join(lines).rstrip() + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(HERE, "..", "docs", "python_api.md"))
    parser.add_argument("--check", action="store_true", help="exit 1 when a public name has no docstring")
    args = parser.parse_args()
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(reference())
    missing = missing_docstrings(ss)
    if args.check and missing:
        print("without a docstring: " + ", ".join(missing), file=sys.stderr)
        return 1
    print("python_api_reference: wrote %s" % args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
