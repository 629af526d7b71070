#!/usr/bin/env python3
"""Checks that the library's modules keep to the floors of docs/architecture.md.

Reads the table of docs/architecture.md (a row per module: its floor and the modules it may use),
the #include "mcws/<module>/..." lines of every module's sources, and the link graph CMake wrote
at configure time (BUILD/mcws_links.txt: one line per target, "target: linked linked ..."). Fails,
one line per problem, when
  - a module includes a module it may not use;
  - a target links a module it may not use;
  - a target links a module none of its module's files includes (a link kept for nothing);
  - a module may use one on its own floor or above (the table itself breaks the floors).
With --dot FILE it also writes the allowed graph for Graphviz (docs/architecture.png).

Usage: scripts/check_layers.py [--links BUILD/mcws_links.txt] [--dot FILE]
Exit 0 when everything keeps to the document, 1 otherwise, 2 for a bad command line.
"""
import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'^\s*#\s*include\s+"mcws/([a-z_]+)/')


def read_floors(doc):
    """{module: (floor, set of modules it may use)} from the table of docs/architecture.md."""
    modules = {}
    for line in doc.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 4 or not cells[1].isdigit():
            continue
        name = cells[0].strip("`")
        uses = {u.strip().strip("`") for u in cells[2].split(",") if u.strip() not in ("", "-")}
        modules[name] = (int(cells[1]), uses)
    return modules


def module_sources(name):
    """The files of a module: src/mcws/<name>/ (filters: filters/; tools: apps/)."""
    folder = {"filters": ROOT / "filters", "tools": ROOT / "apps"}.get(name,
                                                                    ROOT / "src" / "mcws" / name)
    return [p for p in folder.rglob("*") if p.suffix in (".h", ".hpp", ".cpp")]


def module_of_target(target):
    """The module a CMake target belongs to ("mcws::io" and "mcws_io": io), None for others."""
    name = target.replace("mcws::", "mcws_")
    if not name.startswith("mcws_") or name in ("mcws_pcl", "mcws_warnings"):
        return None
    name = name[len("mcws_"):]
    if name == "reachability":
        return "reach"
    if name.startswith("planning_"):
        return "planning"
    if name.startswith("behavior_"):
        return "behavior"
    if name == "app_common" or name in TOOLS:
        return "tools"
    return name


TOOLS = set()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--doc", default=str(ROOT / "docs" / "architecture.md"))
    parser.add_argument("--links", help="mcws_links.txt of a configured build")
    parser.add_argument("--dot", help="write the allowed graph here (Graphviz)")
    args = parser.parse_args()

    floors = read_floors(pathlib.Path(args.doc))
    if not floors:
        print(f"check_layers: {args.doc}: no table of modules found", file=sys.stderr)
        return 1
    TOOLS.update(p.stem[len("mcws_"):] for p in (ROOT / "apps").glob("mcws_*.cpp"))
    problems = []
    for name, (floor, uses) in sorted(floors.items()):
        for used in sorted(uses):
            if used not in floors:
                problems.append(f"{args.doc}: '{name}' may use '{used}', which is not in the table")
            elif floors[used][0] >= floor:
                problems.append(f"{args.doc}: '{name}' (floor {floor}) may use '{used}' "
                                f"(floor {floors[used][0]}): a module uses only lower floors")

    included = {}
    for name in floors:
        included[name] = set()
        for path in module_sources(name):
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                match = INCLUDE.match(line)
                if not match or match.group(1) == name:
                    continue
                used = match.group(1)
                included[name].add(used)
                if used not in floors[name][1]:
                    problems.append(f"{path.relative_to(ROOT)}:{number}: '{name}' includes "
                                    f"'{used}', which docs/architecture.md does not let it use")

    if args.links:
        for line in pathlib.Path(args.links).read_text().splitlines():
            target, _, linked = line.partition(":")
            name = module_of_target(target.strip())
            if name is None or name not in floors:
                continue
            for item in linked.split():
                used = module_of_target(re.sub(r"^\$<LINK_ONLY:(.*)>$", r"\1", item))
                if used is None or used == name:
                    continue
                if used not in floors[name][1]:
                    problems.append(f"{args.links}: target {target.strip()} ('{name}') links "
                                    f"'{used}', which docs/architecture.md does not let it use")
                elif used not in included[name] and name != "tools":
                    problems.append(f"{args.links}: target {target.strip()} ('{name}') links "
                                    f"'{used}' but no file of '{name}' includes it")

    if args.dot:
        lines = ["digraph floors {", '  node [shape=box, fontname="Helvetica"];']
        for floor in sorted({f for f, _ in floors.values()}):
            same = " ".join(f'"{n}";' for n, (f, _) in sorted(floors.items()) if f == floor)
            lines.append(f"  {{ rank=same; {same} }}")
        for name, (_, uses) in sorted(floors.items()):
            for used in sorted(uses):
                lines.append(f'  "{name}" -> "{used}";')
        lines.append("}")
        pathlib.Path(args.dot).write_text("\n".join(lines) + "\n")

    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
