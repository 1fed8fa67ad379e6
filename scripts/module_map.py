#!/usr/bin/env python3
"""The module map of docs/architecture.md, generated from the code's own #include lines.

A module is a folder directly under core/ or server/ (its subfolders are concepts inside it). An arrow
A --> B means some file of A includes a header of B. The map is a Mermaid graph between the markers
`<!-- module-map:begin -->` and `<!-- module-map:end -->` of docs/architecture.md.

  scripts/module_map.py            rewrite the map in docs/architecture.md
  scripts/module_map.py --check    exit 1 when the map differs from the includes, or when a module folder
                                   is not named on the page (as `core/<name>/` or `server/<name>/`)
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "architecture.md"
BEGIN, END = "<!-- module-map:begin -->", "<!-- module-map:end -->"
INCLUDE = re.compile(r'^\s*#\s*include\s+"((?:core|server)/[^"]+)"', re.M)
SOURCES = (".cpp", ".hpp", ".h", ".cpp.in")


def module_of(relative: str) -> str:
    """core/contact/geometry/x.hpp -> core/contact; core/simulate.hpp -> core (files at a root)."""
    parts = relative.split("/")
    return "/".join(parts[:2]) if len(parts) > 2 else parts[0]


def modules() -> list:
    found = []
    for top in ("core", "server"):
        for folder in sorted((ROOT / top).iterdir()):
            if folder.is_dir() and any(p.name.endswith(SOURCES) for p in folder.rglob("*")):
                found.append(f"{top}/{folder.name}")
    return found


def edges() -> set:
    result = set()
    for top in ("core", "server"):
        for path in (ROOT / top).rglob("*"):
            if not path.is_file() or not path.name.endswith(SOURCES):
                continue
            source = module_of(path.relative_to(ROOT).as_posix())
            for target in INCLUDE.findall(path.read_text(errors="replace")):
                target_module = module_of(target)
                if target_module != source:
                    result.add((source, target_module))
    return result


def node_id(module: str) -> str:
    return module.replace("/", "_")


def diagram() -> str:
    names = sorted(set(modules()) | {m for edge in edges() for m in edge})
    lines = [BEGIN, "```mermaid", "graph TD"]
    lines += [f'  {node_id(m)}["{m}"]' for m in names]
    lines += [f"  {node_id(a)} --> {node_id(b)}" for a, b in sorted(edges())]
    lines += ["```", END]
    return "\n".join(lines)


def current_block(text: str) -> str:
    start, end = text.find(BEGIN), text.find(END)
    if start < 0 or end < 0:
        sys.exit(f"{PAGE}: markers {BEGIN} … {END} are missing")
    return text[start : end + len(END)]


def main() -> int:
    text = PAGE.read_text()
    wanted = diagram()
    if "--check" not in sys.argv:
        PAGE.write_text(text.replace(current_block(text), wanted))
        return 0
    failures = []
    if current_block(text) != wanted:
        failures.append("the module map differs from the includes: run scripts/module_map.py and commit")
    outside_map = text.replace(current_block(text), "")
    for module in modules():
        # the Layout block describes each module on a line of its own: "  <name>/   what it is for"
        if not re.search(rf"^  {re.escape(module.split('/')[1])}/\s+\S", outside_map, re.M):
            failures.append(f"module folder {module}/ is not described on docs/architecture.md")
    for failure in failures:
        print(f"module_map: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
